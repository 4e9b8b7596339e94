#version 450 core
// Liktor & Dachsbacher 2011 §4.2: the hierarchical projected grid. Each
// cell of the current level is kept as the base of two beams, split into
// four (appended to the next level's list: a compute shader with an append
// buffer, the paper's future work, in place of geometry-shader stream-out)
// or discarded, by the split oracle:
// - coverage: a cell whose lattice vertices are partly off the specular
//   surfaces (or whose rays leave through different interfaces, or meet
//   total internal reflection differently) crosses a silhouette;
// - discontinuities of the surface: normals or depths of the corners apart;
// - energy: convergent beams (the cross-section shrinks below `u_focus` of
//   the base along the extrusion) are split first, divergent ones are not;
// - the camera: a beam whose width seen from the camera (at the point of
//   its central ray nearest to it) exceeds `u_pixels` pixels.
// Past `refine` levels, a cell is split only at a silhouette (`edges` more
// levels), where the beams' edges would otherwise leave a ragged ring with
// no light. Cells are addressed on the finest lattice, so neighbouring beams of any
// level share their corner rays exactly (the adjacency the paper loses
// after stream-out, §7).
#include "common/frame.glsl"
#include "beam_caustics/beams.glsl"
layout(local_size_x = 64) in;
uniform int u_in_offset, u_out_offset; // this level's lists (the rest: BeamParams, beams.glsl)

bool valid_vertex(int i, int j)
{
    uint f = uint(beam_vertices[vertex_index(i, j)].exit_pos.w + 0.5);
    return (f & VERTEX_SURFACE) != 0u;
}

// The cross-section ratio A(y)/A(0) at the far end of the quad's rays (a
// quad: the parallelogram of two of its triangles, enough for the oracle).
float focus_ratio(vec3 v[4], vec3 d[4], float len)
{
    vec3 e1 = v[1] - v[0], e2 = v[3] - v[0];
    vec3 n = cross(e1, e2);
    float a0 = length(n);
    if (a0 < 1e-20)
        return 0.0; // a degenerate base: treat as focused
    n /= a0;
    float ratio = 1.0;
    for (int s = 1; s <= 4; s++) {
        float t = len * float(s) / 4.0;
        vec3 q1 = v[1] + d[1] * t - (v[0] + d[0] * t), q2 = v[3] + d[3] * t - (v[0] + d[0] * t);
        ratio = min(ratio, dot(cross(q1, q2), n) / a0); // signed: a flip counts as a focus
    }
    return ratio;
}

// 0: discard, 1: keep, 2: split
int decide(uint k, out int level, out int x, out int y)
{
    cell_unpack(cells[u_in_offset + int(k)], level, x, y);
    int step = 1 << (u_refine - level);
    int i0 = x * step, j0 = y * step;
    // coverage over the cell's lattice vertices
    int covered = 0, total = (step + 1) * (step + 1);
    for (int j = 0; j <= step; j++)
        for (int i = 0; i <= step; i++)
            covered += valid_vertex(i0 + i, j0 + j) ? 1 : 0;
    if (covered == 0)
        return 0; // nothing specular here
    bool split = covered < total;
    ivec2 corner[4] = ivec2[4](ivec2(i0, j0), ivec2(i0 + step, j0), ivec2(i0 + step, j0 + step), ivec2(i0, j0 + step));
    BeamVertex c[4];
    for (int q = 0; q < 4; q++)
        c[q] = beam_vertices[vertex_index(corner[q].x, corner[q].y)];
    if (!split) {
        // the path's kind (transmitted or not, interfaces, total internal reflections)
        uint f0 = uint(c[0].exit_pos.w + 0.5);
        for (int q = 1; q < 4; q++) {
            uint fq = uint(c[q].exit_pos.w + 0.5);
            if (fq != f0 || c[q].exit_weight.w != c[0].exit_weight.w)
                split = true;
        }
    }
    // a silhouette (of the glass, or between paths) is refined `u_edges` levels further
    bool silhouette = split;
    if (level >= u_free)
        return silhouette && level < u_refine ? 2 : 1;
    if (!split) {
        // discontinuities of the surface: normals apart, or a depth step steeper than
        // u_depth_jump times the cell's side across the light's view (a slope of atan(u_depth_jump))
        float lo_d = c[0].refl_pos.w, hi_d = lo_d;
        for (int q = 0; q < 4; q++) {
            for (int r = q + 1; r < 4; r++)
                if (dot(c[q].normal.xyz, c[r].normal.xyz) < u_normal_cos)
                    split = true;
            lo_d = min(lo_d, c[q].refl_pos.w);
            hi_d = max(hi_d, c[q].refl_pos.w);
        }
        float side = distance(c[0].light_plane.xy, c[2].light_plane.xy) * (u_light_ortho == 1 ? 1.0 : lo_d);
        if (hi_d - lo_d > u_depth_jump * side)
            split = true;
    }
    uint f = uint(c[0].exit_pos.w + 0.5);
    if (!split && (f & VERTEX_TRANSMITTED) != 0u) {
        // energy: convergent beams first
        vec3 v[4], d[4];
        float len = 1e30;
        for (int q = 0; q < 4; q++) {
            v[q] = c[q].exit_pos.xyz;
            d[q] = c[q].exit_dir.xyz;
            len = min(len, c[q].exit_dir.w);
        }
        if (focus_ratio(v, d, len) < u_focus)
            split = true;
        // the camera: the beam's width where its central ray passes nearest to the eye
        vec3 o = 0.25 * (v[0] + v[1] + v[2] + v[3]);
        vec3 dc = normalize(d[0] + d[1] + d[2] + d[3]);
        float t = clamp(dot(u_camera_pos.xyz - o, dc), 0.0, len);
        vec3 near_point = o + dc * t;
        float dist = max(distance(near_point, u_camera_pos.xyz), 1e-4);
        float width = 0.0;
        for (int q = 0; q < 2; q++)
            width = max(width, distance(v[q] + d[q] * t, v[q + 2] + d[q + 2] * t));
        float pixels = camera_is_ortho() ? width * u_proj[1][1] * 0.5 * u_viewport.y
                                         : width / dist * u_proj[1][1] * 0.5 * u_viewport.y;
        if (pixels > u_pixels)
            split = true;
    }
    return split && level < u_refine ? 2 : 1; // (level < u_free here)
}

void main()
{
    uint k = gl_GlobalInvocationID.x;
    int level = 0, x = 0, y = 0, action = 0;
    if (k < counters[COUNT_IN])
        action = decide(k, level, x, y);
    // the appends in uniform control flow: every invocation adds (perhaps 0)
    uint at_next = atomicAdd(counters[COUNT_NEXT], action == 2 ? 4u : 0u);
    uint at_kept = atomicAdd(counters[COUNT_KEPT], action == 1 ? 1u : 0u);
    if (action == 2) {
        if (at_next + 4u > uint(u_capacity)) {
            atomicAdd(counters[COUNT_OVERFLOW], 1u);
            return;
        }
        for (int q = 0; q < 4; q++)
            cells[u_out_offset + int(at_next) + q] = cell_pack(level + 1, 2 * x + (q & 1), 2 * y + (q >> 1));
    } else if (action == 1) {
        if (at_kept >= uint(u_capacity)) {
            atomicAdd(counters[COUNT_OVERFLOW], 1u);
            return;
        }
        cells[u_kept_offset + int(at_kept)] = cells[u_in_offset + int(k)];
    }
}
