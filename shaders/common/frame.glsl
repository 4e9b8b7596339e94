#include "common/bindings.glsl"
// Per-frame data shared by every pass: one std140 block at binding 0
// (mirrored by struct renderer_frame_uniforms in src/graph/renderer.h) and
// the environment cube map at unit 15.
struct GpuLight {
    vec4 position;   // xyz, w = kind: 0 point, 1 directional, 2 spot
    vec4 direction;  // xyz (direction light travels / spot axis), w = cos(outer)
    vec4 intensity;  // rgb, w = cos(inner)
};

layout(std140, binding = BINDING_FRAME) uniform Frame {
    mat4 u_view;
    mat4 u_proj;
    mat4 u_view_proj;
    mat4 u_inv_view_proj;
    vec4 u_camera_pos;  // w = time in seconds
    vec4 u_viewport;    // width, height, 1/width, 1/height
    vec4 u_background;  // rgb, w = 1 when an environment map is bound
    vec4 u_ambient;
    ivec4 u_counts;     // x = number of lights, y = frame
    GpuLight u_lights[32];
};

layout(binding = UNIT_ENVIRONMENT) uniform samplerCube u_environment;

const float PI = 3.14159265358979;

// Radiance arriving from direction `dir` (world space) from far away.
vec3 environment_radiance(vec3 dir)
{
    return u_background.w > 0.5 ? texture(u_environment, dir).rgb : u_background.rgb;
}
