#version 450 core
// Recursive reflection/refraction (Hu & Qin §2.2, Fig. 1b, 24g): a
// reflector's or refractor's impostor drawn again, now reflecting and
// refracting (one interface) the previous level's impostors of the other
// objects, or the environment where none is hit.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "impostors/impostors.glsl"
#include "common/roles.glsl"
in vec3 v_world;
in vec3 v_normal;
uniform vec3 u_impostor_center;
uniform vec3 u_impostor_axis;
uniform vec3 u_color;
uniform float u_ior;
uniform float u_ideal;
layout(location = 0) out vec4 o_depth;
layout(location = 1) out vec4 o_color;

vec3 look(vec3 o, vec3 d)
{
    vec3 c;
    if (impostor_lookup(o, d, 3, c))
        return c;
    return environment_radiance(d);
}

void main()
{
    o_depth = vec4(dot(v_world - u_impostor_center, u_impostor_axis), 0.0, 0.0, 1.0);
    vec3 n = normalize(v_normal);
    vec3 v = u_impostor_axis;
    if (dot(n, v) > 0.0)
        n = -n;
    vec3 reflected = look(v_world, reflect(v, n));
    if (role_is(ROLE_MIRROR)) {
        o_color = vec4(u_color * reflected, 1.0);
        return;
    }
    float f = fresnel_of(-dot(v, n), 1.0 / u_ior, u_ideal);
    vec3 t = refract_or_reflect(v, n, 1.0 / u_ior);
    o_color = vec4(f * reflected + (1.0 - f) * look(v_world, t), 1.0);
}
