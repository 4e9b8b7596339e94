#version 450 core
// An object in world space: its world position, normal and texture
// coordinates, projected by the camera, or, where a program defines
// OBJECT_VIEW_PROJ, by u_object_view_proj (a distance map's cube face, an
// impostor's view, a light's): the one object vertex shader of shade, the
// receivers, the water surface, the distance maps and the impostors. (The
// define once named the uniform itself: four names C set that no shader
// declared, which tests/cli/uniform_names_test.sh now refuses.)
#include "common/frame.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord0;
layout(location = 3) in vec2 a_texcoord1;
layout(location = 4) in vec4 a_color; // glTF's COLOR_0
layout(location = 5) in vec4 a_tangent; // a normal map's tangent (u_has_tangents; common/material.glsl)
uniform int u_vertex_colors;          // 0: the mesh has none (white)
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
#ifdef OBJECT_VIEW_PROJ
uniform mat4 u_object_view_proj;
#endif
out vec3 v_world;
out vec3 v_normal;
out vec2 v_texcoord0;
out vec2 v_texcoord1;
out vec4 v_color;
out vec4 v_tangent; // world xyz (by the model matrix, as the reference's mapped_normal), w
void main()
{
    v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
    v_color = u_vertex_colors == 1 ? a_color : vec4(1.0);
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_texcoord0 = a_texcoord0;
    v_texcoord1 = a_texcoord1;
#ifdef OBJECT_VIEW_PROJ
    gl_Position = u_object_view_proj * w;
#else
    gl_Position = u_view_proj * w;
#endif
}
