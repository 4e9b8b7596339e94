#include "passes/helpers/virtual_camera.h"

#include <math.h>

#include "gl/gl_api.h"

void virtual_camera_axes(struct virtual_camera *vc, vec3 d)
{
    vec3 helper = fabsf(d.y) < 0.9f ? vec3_make(0, 1, 0) : vec3_make(1, 0, 0);
    vc->d = d;
    vc->u = vec3_normalize_or(vec3_cross(helper, d), vec3_make(1, 0, 0));
    vc->v = vec3_cross(d, vc->u);
}

void virtual_camera_set(const struct gl_program *prog, const struct virtual_camera *vc)
{
    GLuint id = prog->id;
    gl.ProgramUniform3f(id, gl_program_uniform(prog, "u_vc_d"), vc->d.x, vc->d.y, vc->d.z);
    gl.ProgramUniform3f(id, gl_program_uniform(prog, "u_vc_u"), vc->u.x, vc->u.y, vc->u.z);
    gl.ProgramUniform3f(id, gl_program_uniform(prog, "u_vc_v"), vc->v.x, vc->v.y, vc->v.z);
    gl.ProgramUniform3f(id, gl_program_uniform(prog, "u_vc_center"), vc->center[0], vc->center[1], 0.0f);
    gl.ProgramUniform1f(id, gl_program_uniform(prog, "u_vc_half"), vc->half);
    gl.ProgramUniform2f(id, gl_program_uniform(prog, "u_vc_depth"), vc->near, vc->far);
}
