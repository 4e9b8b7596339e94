#version 450 core
// Iwasaki et al. §3 ([13]): the sliced object images mapped onto the glass.
// The viewing ray leaving the object meets the slices' planes in order of
// depth; the first slice holding a target there gives the refracted view;
// past all of them the environment. Plus the Fresnel reflection at the
// front surface.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "illumination_textures/virtual_camera.glsl"
uniform sampler2DArray u_slices;
uniform float u_ior;   // the object's (set per object, as it is drawn)
uniform float u_ideal;
// The pass's values (issue 54: one block, mirrored by struct sliced_glass_params)
layout(std140) uniform SlicedGlassParams {
    float u_plane[17];  // the slabs' planes along the virtual camera's axis (SLICED_MAX_SLICES + 1)
    int u_slices_count;
    int u_reflection;   // 1: the Fresnel reflection at the front surface
};
in vec3 v_world;
in vec3 v_normal;
in vec3 v_exit_position;
in vec3 v_exit_direction;
in vec3 v_transmittance;
in float v_valid;
layout(location = 0) out vec4 o_color;

vec3 through_slices(vec3 o, vec3 d)
{
    float cd = dot(d, u_vc_d);
    for (int i = 0; i < u_slices_count; i++) {
        if (cd <= 1e-4)
            break;
        float t = (u_plane[i] - dot(o, u_vc_d)) / cd;
        if (t < 0.0) {
            // the ray leaves the glass inside this slab: it starts there
            if (dot(o, u_vc_d) >= u_plane[i + 1])
                continue;
            t = 0.0;
        }
        vec2 uv = vc_uv(o + d * t);
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
            continue;
        vec4 s = texture(u_slices, vec3(uv, float(i)));
        if (s.a > 0.5)
            return s.rgb / s.a;
    }
    return environment_radiance(d);
}

void main()
{
    vec3 n = normalize(v_normal);
    vec3 v = view_direction(v_world);
    if (dot(v, n) > 0.0)
        n = -n;
    float f = fresnel_of(-dot(v, n), 1.0 / u_ior, u_ideal);
    vec3 color = vec3(0.0);
    // The vertices without a path write zeros (and w 0): the interpolated
    // exits divided by the interpolated validity are the mean of the
    // vertices that have one. A triangle with one corner on the silhouette
    // (a cube's corners graze the view) still refracts, as its other
    // corners say; while it needed all three, every face of an IOR-1.0 cube
    // showed the environment's reflection, one smooth colour each.
    if (v_valid > 1e-3) {
        color += (1.0 - f) * (v_transmittance / v_valid) *
                 through_slices(v_exit_position / v_valid, normalize(v_exit_direction));
    } else {
        // no path through the table here (the silhouette, or total internal
        // reflection): the light comes back out as reflection
        f = 1.0;
    }
    if (u_reflection == 1 || f >= 1.0)
        color += f * environment_radiance(reflect(v, n));
    o_color = vec4(color, 1.0);
}
