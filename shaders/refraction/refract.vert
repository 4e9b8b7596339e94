#version 450 core
// The refractor's surfaces for refraction's two passes (surfaces.frag: the front
// and back normals and depths; refract.frag: the refraction itself).
#include "common/frame.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord0;
layout(location = 3) in vec2 a_texcoord1;
layout(location = 4) in vec4 a_color;   // glTF's COLOR_0 (its alpha cuts out or blends: common/alpha.glsl)
layout(location = 5) in vec4 a_tangent; // a normal map's (common/normal_map.glsl)
uniform int u_vertex_colors;           // 0: the mesh has none (white)
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
out vec3 v_normal;
out vec3 v_world;
out float v_thickness;
out vec2 v_texcoord0; // for glass's transmission texture (refract.frag)
out vec2 v_texcoord1;
out vec4 v_tangent;
out vec4 v_color;
#ifdef WYMAN
layout(std430) readonly buffer Thickness { float thickness[]; };
#endif
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_world = w.xyz;
    v_texcoord0 = a_texcoord0;
    v_texcoord1 = a_texcoord1;
    v_color = u_vertex_colors == 1 ? a_color : vec4(1.0);
    v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
#ifdef WYMAN
    // d_N scales with the object (uniform scale assumed)
    v_thickness = thickness[gl_VertexID] * length(mat3(u_model)[0]);
#else
    v_thickness = 0.0;
#endif
    gl_Position = u_view_proj * w;
}
