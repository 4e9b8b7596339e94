#version 450 core
// Sandberg & Falemo §3.5, third pass: the pool's image mapped onto the
// surface by refraction against a virtual plane (the floor, `u_depth`
// below the mean level), absorbed on the way, plus the Fresnel-weighted
// reflection of the environment.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_scene;
uniform sampler2D u_scene_depth;
uniform sampler2D u_scene_position;
uniform float u_ior;
uniform float u_ideal;
uniform vec3 u_absorption;
// The pass's values (issue 54: one block, mirrored by struct water_surface_params)
layout(std140) uniform WaterSurfaceParams {
    float u_depth;          // the pool's depth below the surface
    float u_level;          // the surface's mean height
    int u_refract_mapping;  // 0: the paper's virtual plane at the mean level; 1: the refracted ray
    int u_eye_in_water;     // the camera under water: the path from the surface to it absorbs too
};

// The scene image seen along a ray from P in direction d down to the
// virtual plane, with the absorption over the distance to what is there.
vec3 through_water(vec3 P, vec3 d)
{
    float t = (P.y - (u_level - u_depth)) / max(-d.y, 0.05);
    // §3.5: the texture coordinates of the virtual plane at the mean water
    // level under P, or the point the refracted ray reaches on the floor
    vec3 target = u_refract_mapping == 1 ? P + d * t : vec3(P.x, u_level, P.z);
    vec4 clip = u_view_proj * vec4(target, 1.0);
    vec2 uv = clip.w > 0.0 ? clamp(clip.xy / clip.w * 0.5 + 0.5, 0.0, 1.0) : vec2(0.5);
    vec3 c = texture(u_scene, uv).rgb;
    vec4 q = texture(u_scene_position, uv);
    float dist = q.w > 0.0 ? length(q.xyz - P) : t;
    return c * exp(-u_absorption * dist);
}

void main()
{
    // hidden behind something nearer than the surface
    float scene_depth = texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r;
    if (gl_FragCoord.z > scene_depth)
        discard;
    vec3 n = normalize(v_normal);
    vec3 v = view_direction(v_world);
    vec3 color;
    if (dot(v, n) < 0.0) {
        // from above: reflect the sky, refract into the pool
        float f = fresnel_of(-dot(v, n), 1.0 / u_ior, u_ideal);
        vec3 t = refract(v, n, 1.0 / u_ior);
        color = f * environment_radiance(reflect(v, n)) + (1.0 - f) * through_water(v_world, t);
    } else {
        // from below: out into the air, or total internal reflection
        vec3 nn = -n;
        float f = fresnel_of(-dot(v, nn), u_ior, u_ideal);
        vec3 t = refract(v, nn, u_ior);
        vec3 reflected = through_water(v_world, reflect(v, nn));
        color = dot(t, t) > 0.0 ? (1.0 - f) * environment_radiance(normalize(t)) + f * reflected : reflected;
        if (u_eye_in_water == 1)
            color *= exp(-u_absorption * view_distance(v_world));
    }
    o_color = vec4(color, 1.0);
}
