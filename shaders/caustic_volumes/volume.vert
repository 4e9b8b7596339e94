#version 450 core
// Draws volume gl_VertexID / 24 as a closed prism of 8 triangles (top,
// bottom, three sides of two triangles), wound counter-clockwise seen from
// outside so back faces can be culled (§3.5).
#include "common/frame.glsl"
#include "caustic_volumes/volume.glsl"
flat out int v_volume;

// The world size of one pixel at p (the larger of its two sides).
float pixel_footprint(vec3 p)
{
    float per_unit = 2.0 / min(u_proj[0][0] * u_viewport.x, u_proj[1][1] * u_viewport.y);
    if (camera_is_ortho())
        return per_unit;
    float depth = max(-(u_view * vec4(p, 1.0)).z, 1e-4);
    return per_unit * depth;
}

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
    // Each corner moves an eighth of a pixel outward from its triangle's centre, in
    // that triangle's plane. The fragment shader decides membership by the
    // receiver point against the exact cut (with its own half-open rule);
    // the rasterizer's coverage of the exact prism follows another rule
    // (top-left, on the faces, not at the receiver), and where the two
    // disagree a pixel whose receiver lies exactly on a shared edge was
    // counted by no volume: whole rows (all of them, with an orthographic
    // camera whose pixel centres fall on the grid) were black. A slightly
    // larger prism is covered by exactly one face wherever the exact one is,
    // so the fragment test alone decides (§3.5's point-in-volume test). An
    // eighth of a pixel is far more than the rasterizer's snapping (1/256 of
    // a pixel) and, unlike a whole pixel, adds few fragments to a fine
    // generator grid (a whole pixel cost the pool 2.5x at resolution 256).
    vec3 centre = c < 3 ? (volumes[id].top[0].xyz + volumes[id].top[1].xyz + volumes[id].top[2].xyz) / 3.0
                        : (volumes[id].bottom[0].xyz + volumes[id].bottom[1].xyz + volumes[id].bottom[2].xyz) / 3.0;
    vec3 out_dir = p - centre;
    float out_len = length(out_dir);
    if (out_len > 0.0)
        p += out_dir / out_len * (0.125 * pixel_footprint(p));
    if (volumes[id].flux.w <= 0.0)
        p = vec3(0.0); // empty volume: a degenerate triangle draws nothing
    gl_Position = u_view_proj * vec4(p, 1.0);
}
