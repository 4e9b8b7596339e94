#version 450 core
// Every draw of a refractor into its depth layers: world normal and eye
// depth (the distance along the view's axis) per vertex.
#include "layers/layers.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
out vec3 v_normal;
out float v_depth;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    vec4 e = u_layer_view * w;
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_depth = -e.z;
    gl_Position = u_layer_proj * e;
}
