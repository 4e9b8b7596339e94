#version 450 core
// Draws volume gl_VertexID / 24 as a closed prism of 8 triangles (top,
// bottom, three sides of two triangles), wound counter-clockwise seen from
// outside so back faces can be culled (§3.5).
#include "common/frame.glsl"
#include "caustic_volumes/volume.glsl"
flat out int v_volume;
// corners 0-2 on the surface, 3-5 below; the surface triangle is
// counter-clockwise seen from above
const int corners[24] = int[24](0, 1, 2,   3, 5, 4,
                                0, 3, 1,   1, 3, 4,
                                1, 4, 2,   2, 4, 5,
                                2, 5, 0,   0, 5, 3);
void main()
{
    int id = gl_VertexID / 24;
    int c = corners[gl_VertexID % 24];
    v_volume = id;
    vec3 p = c < 3 ? volumes[id].top[c].xyz : volumes[id].bottom[c - 3].xyz;
    if (volumes[id].flux.w <= 0.0)
        p = vec3(0.0); // empty volume: a degenerate triangle draws nothing
    gl_Position = u_view_proj * vec4(p, 1.0);
}
