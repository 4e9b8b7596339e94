#version 450 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_face_view_proj;
out vec3 v_world;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    gl_Position = u_face_view_proj * w;
}
