#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 2) in vec2 a_texcoord0;
layout(location = 3) in vec2 a_texcoord1;
layout(location = 4) in vec4 a_color; // glTF's COLOR_0 (its alpha cuts out, as the base colour's)
uniform int u_vertex_colors;
uniform mat4 u_model;
uniform mat4 u_light_view_proj;
out vec3 v_world;
out vec2 v_texcoord0; // for the cut-outs of common/material.glsl
out vec2 v_texcoord1;
out vec4 v_color;
out vec4 v_tangent; // (common/material.glsl declares it; a shadow needs no normal map)
void main()
{
    v_color = u_vertex_colors == 1 ? a_color : vec4(1.0);
    v_tangent = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_texcoord0 = a_texcoord0;
    v_texcoord1 = a_texcoord1;
    gl_Position = u_light_view_proj * w;
}
