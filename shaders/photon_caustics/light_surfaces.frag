#version 450 core
// The refractors from the light: the outward normal and what the photon
// meets there (w: -1 a mirror, else the index of refraction), and the
// material's absorption (rgb) and kind (w: 3 water, one interface).
in vec3 v_normal;
in float v_thickness;
uniform int u_material_kind;
uniform vec3 u_absorption;
uniform vec3 u_color;
layout(location = 0) out vec4 o_normal;
layout(location = 1) out vec4 o_material;
void main()
{
    o_normal = vec4(normalize(v_normal), v_thickness);
    // a mirror's tint in place of the absorption
    o_material = vec4(u_material_kind == 2 ? u_color : u_absorption, float(u_material_kind));
}
