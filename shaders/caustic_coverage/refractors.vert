#version 450 core
// The refractors' depth from a caustics pass's light (caustic_coverage.c).
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_light_view_proj;
void main()
{
    gl_Position = u_light_view_proj * (u_model * vec4(a_position, 1.0));
}
