#version 450 core
// The refractors from the light: the outward normal and what the photon
// meets there (w: -1 a mirror, else the index of refraction), and the
// material's absorption (rgb) and roles (w: common/roles.glsl's bits;
// water has one interface).
#include "common/roles.glsl"
in vec3 v_normal;
in float v_thickness;
uniform vec3 u_absorption;
uniform vec3 u_color;
layout(location = 0) out vec4 o_normal;
layout(location = 1) out vec4 o_material;
void main()
{
    o_normal = vec4(normalize(v_normal), v_thickness);
    // a mirror's tint in place of the absorption
    o_material = vec4(role_is(ROLE_MIRROR) ? u_color : u_absorption, float(u_object_role));
}
