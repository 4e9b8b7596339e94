#version 450 core
// The part of the targets between planes u_slab.x and u_slab.y along the
// viewing direction, projected onto the slab's first plane. Its colour is
// what the camera shows there where the camera sees that point (caustics
// and shadows included), else the one lighting function shade uses
// (common/surface_light.glsl; the pass has no shadow maps, so unshadowed,
// and no caustics).
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"
#include "illumination_textures/virtual_camera.glsl"
uniform sampler2D u_scene;
uniform sampler2D u_scene_depth;
uniform vec2 u_slab;
uniform vec3 u_color;
uniform vec3 u_emission;
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
void main()
{
    float z = vc_depth(v_world);
    if (z < u_slab.x || z >= u_slab.y)
        discard;
    vec4 c = u_view_proj * vec4(v_world, 1.0);
    if (c.w > 0.0) {
        vec2 uv = c.xy / c.w * 0.5 + 0.5;
        if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
            ivec2 px = ivec2(uv * u_viewport.xy);
            float d = texelFetch(u_scene_depth, px, 0).r;
            float seen = view_depth(d), here = -(u_view * vec4(v_world, 1.0)).z;
            if (d < 1.0 && abs(seen - here) < 0.01 * here + 1e-3) {
                o_color = vec4(texelFetch(u_scene, px, 0).rgb, 1.0);
                return;
            }
        }
    }
    vec3 n = normalize(v_normal);
    if (dot(n, u_vc_d) > 0.0)
        n = -n; // the side the viewing rays arrive at
    o_color = vec4(surface_light_diffuse(v_world, n, u_color, u_emission, vec3(0.0)), 1.0);
}
