#version 450 core
// The refractor's surfaces for refraction's two passes (surfaces.frag: the front
// and back normals and depths; refract.frag: the refraction itself).
#include "common/frame.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
out vec3 v_normal;
out vec3 v_world;
out float v_thickness;
#ifdef WYMAN
layout(std430) readonly buffer Thickness { float thickness[]; };
#endif
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_normal = mat3(u_normal_matrix) * a_normal;
    v_world = w.xyz;
#ifdef WYMAN
    // d_N scales with the object (uniform scale assumed)
    v_thickness = thickness[gl_VertexID] * length(mat3(u_model)[0]);
#else
    v_thickness = 0.0;
#endif
    gl_Position = u_view_proj * w;
}
