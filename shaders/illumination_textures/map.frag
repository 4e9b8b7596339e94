#version 450 core
// §4.3, Fig. 5: a receiver point P seen by the camera reads the
// illumination textures at its virtual-camera coordinates: in shadow (the
// normal map's depth is nearer) it gets none; else the two planes around
// its depth are interpolated (a point before the first or past the last
// plane reads that plane).
#include "common/frame.glsl"
#include "illumination_textures/virtual_camera.glsl"
uniform sampler2D u_target;
uniform sampler2DArray u_textures;
// The pass's values (issue 54: one block, mirrored by struct illumination_map_params)
layout(std140) uniform IlluminationMapParams {
    float u_plane_depth[16]; // the virtual planes' depths along the virtual camera (ILLUM_MAX_PLANES)
    int u_planes;
    float u_bias;            // the shadow test's tolerance
};
in vec3 v_world;
layout(location = 0) out vec4 o_irradiance;
void main()
{
    vec2 uv = vc_uv(v_world);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        o_irradiance = vec4(0.0);
        return;
    }
    float z = vc_depth(v_world);
    float first = texture(u_target, uv).w;
    if (z > first + u_bias) { // another part of the targets is nearer the light
        o_irradiance = vec4(0.0);
        return;
    }
    int i = 0;
    while (i + 1 < u_planes - 1 && z >= u_plane_depth[i + 1])
        i++;
    int j = min(i + 1, u_planes - 1);
    float span = u_plane_depth[j] - u_plane_depth[i];
    float a = span > 0.0 ? clamp((z - u_plane_depth[i]) / span, 0.0, 1.0) : 0.0;
    vec3 e = mix(texture(u_textures, vec3(uv, float(i))).rgb, texture(u_textures, vec3(uv, float(j))).rgb, a);
    o_irradiance = vec4(e, 1.0);
}
