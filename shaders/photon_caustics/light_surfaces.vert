#version 450 core
// The refractors seen from the light (front or back faces, by culling).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
uniform mat4 u_light_view_proj;
out vec3 v_normal;
out float v_thickness;
void main()
{
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_thickness = 0.0;
    gl_Position = u_light_view_proj * (u_model * vec4(a_position, 1.0));
}
