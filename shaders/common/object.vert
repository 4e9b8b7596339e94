#version 450 core
// An object in world space for the camera: its world position and normal
// (fragment shaders that need only these: receivers, G-buffers).
#include "common/frame.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
out vec3 v_world;
out vec3 v_normal;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    gl_Position = u_view_proj * w;
}
