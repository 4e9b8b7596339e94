#include "scene/light_view.h"

#include <math.h>

bool light_view_fit(bool ortho, vec3 position, vec3 direction, vec3 center, float radius,
                    const struct light_view_margins *m, struct light_view *out)
{
    float r = fmaxf(radius, 1e-4f) * m->radius_scale;
    vec3 up = vec3_make(0, 1, 0);
    out->ortho = ortho;
    out->distance = 0.0f;
    if (ortho) {
        vec3 d = vec3_normalize_or(direction, vec3_make(0, -1, 0));
        if (m->up_z_when_vertical && fabsf(d.y) > 0.99f)
            up = vec3_make(0, 0, 1);
        vec3 eye = vec3_sub(center, vec3_scale(d, m->eye_radii * r));
        out->view = mat4_look_at(eye, center, up);
        out->proj = mat4_ortho(-r, r, -r, r, m->ortho_near_radii * r, m->ortho_far_radii * r);
        out->half_extent = out->half_width = out->half_height = r;
        return true;
    }
    vec3 to = vec3_sub(center, position);
    float dist = vec3_length(to);
    float half;
    if (dist > r * (m->inside_half_angle > 0.0f ? 1.0f : 1.001f))
        half = asinf(fminf(r / dist, 1.0f));
    else if (m->inside_half_angle > 0.0f)
        half = m->inside_half_angle;
    else
        return false;
    if (m->up_z_when_vertical && fabsf(to.y) > 0.99f * dist)
        up = vec3_make(0, 0, 1);
    float fov = fminf(2.0f * half * 180.0f / (float)MATH_PI * m->fov_scale, 170.0f);
    out->view = mat4_look_at(position, center, up);
    out->proj = mat4_perspective(fov, 1.0f, fmaxf(dist - r, 1e-3f) * m->near_scale, dist + m->far_radii * r);
    out->half_extent = tanf(fov * 0.5f * (float)MATH_PI / 180.0f);
    out->half_width = out->half_height = out->half_extent;
    out->distance = dist;
    return true;
}
