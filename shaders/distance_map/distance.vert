#version 450 core
// One face of the distance map (src/passes/distance_map.c).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord0;
layout(location = 3) in vec2 a_texcoord1;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
uniform mat4 u_face_view_proj;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_texcoord0;
out vec2 v_texcoord1;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_texcoord0 = a_texcoord0;
    v_texcoord1 = a_texcoord1;
    gl_Position = u_face_view_proj * w;
}
