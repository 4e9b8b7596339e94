#version 450 core
// The refractors seen from the light (front or back faces, by culling).
#include "common/fresnel.glsl"
#include "common/roles.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
uniform mat4 u_light_view_proj;
uniform float u_ior;
uniform float u_ideal;
out vec3 v_normal;
out float v_thickness;
void main()
{
    v_normal = mat3(u_normal_matrix) * a_normal;
    // w of the normal buffer: which material the photon meets here
    // (-1 a mirror, else the index of refraction)
    v_thickness = role_is(ROLE_MIRROR) ? -1.0 : u_ior + (u_ideal > 0.5 ? IDEAL_IOR_OFFSET : 0.0);
    gl_Position = u_light_view_proj * (u_model * vec4(a_position, 1.0));
}
