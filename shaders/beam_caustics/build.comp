#version 450 core
// Liktor & Dachsbacher 2011 §4.3: the beams of the kept cells. Each cell is
// two base triangles (on the finest level, along the diagonal that keeps
// more of them whole at a silhouette); each triangle whose three corners
// carry the same kind of ray makes a transmitted beam and, with
// u_reflection, a reflected one. Per beam: Ernst et al. 2005's beam space
// (y along the base's normal, edge directions scaled to unit height), the
// three coefficients of its area function A(y), and its bounding volume:
// the paper's six triangles, one per edge of the base and the top with a
// vertex of the opposite triangle (Fig. 5 right), or, where a side has
// more than one candidate (near planar) or the two triangles of a side do
// not meet along one diagonal, Ernst's bounding prism of touching planes.
#include "beam_caustics/beams.glsl"
layout(local_size_x = 64) in;
// (its values: BeamParams, beams.glsl)

struct Ray {
    vec3 o, d;
    float len;
    vec3 w;
    vec3 sigma; // absorption per unit length after the ray's origin
    uint flags;
    float signature;
};

Ray vertex_ray(int i, int j, bool reflected)
{
    BeamVertex bv = beam_vertices[vertex_index(i, j)];
    Ray r;
    r.flags = uint(bv.exit_pos.w + 0.5);
    if (reflected) {
        r.o = bv.refl_pos.xyz;
        r.d = bv.refl_dir.xyz;
        r.len = bv.refl_dir.w;
        r.w = bv.refl_weight.rgb;
        r.signature = -1.0;
        r.sigma = vec3(0.0);
    } else {
        r.o = bv.exit_pos.xyz;
        r.d = bv.exit_dir.xyz;
        r.len = bv.exit_dir.w;
        r.w = bv.exit_weight.rgb;
        r.signature = bv.exit_weight.w;
        r.sigma = bv.exit_sigma.rgb;
    }
    return r;
}

bool ray_ok(Ray r, bool reflected)
{
    return (r.flags & (reflected ? VERTEX_REFLECTED : VERTEX_TRANSMITTED)) != 0u;
}

vec2 lattice_plane(ivec2 q) { return beam_vertices[vertex_index(q.x, q.y)].light_plane.xy; }

// The plane through a, b, c with its normal turned away from `inside`.
vec4 plane_away(vec3 a, vec3 b, vec3 c, vec3 inside)
{
    vec3 m = cross(b - a, c - a);
    float len = length(m);
    if (len < 1e-30)
        return vec4(0.0);
    m /= len;
    if (dot(m, inside - a) > 0.0)
        m = -m;
    return vec4(m, -dot(m, a));
}

// How far the farthest of the six points lies outside plane pl (<= tol: it supports the beam).
float violation(vec4 pl, vec3 pts[6])
{
    if (dot(pl.xyz, pl.xyz) == 0.0)
        return 1e30;
    float worst = -1e30;
    for (int k = 0; k < 6; k++)
        worst = max(worst, dot(pl.xyz, pts[k]) + pl.w);
    return worst;
}

bool make_beam(ivec2 qa, ivec2 qb, ivec2 qc, bool reflected, out Beam bm, out bool was_prism)
{
    Ray r[3] = Ray[3](vertex_ray(qa.x, qa.y, reflected), vertex_ray(qb.x, qb.y, reflected),
                      vertex_ray(qc.x, qc.y, reflected));
    // Beam space (Ernst et al. 2005) needs the base in the plane y = 0. The
    // exit triangle itself can be steep to the rays (exits near a
    // silhouette), which would tilt the scan plane of §5.1 along the beam;
    // so the base is moved along the edge rays onto the plane across their
    // mean direction, through the rearmost exit (the beam then starts a
    // little inside the glass, where nothing scatters and nothing receives).
    vec3 m = r[0].d + r[1].d + r[2].d;
    if (dot(m, m) < 1e-12)
        return false;
    vec3 n = normalize(m);
    float plane = min(min(dot(r[0].o, n), dot(r[1].o, n)), dot(r[2].o, n));
    vec3 v[3], d[3];
    float h[3], back[3], top = 0.0;
    // An edge ray that met no receiver (and no medium: extrusion_length gave
    // it 0) beside one that did: near a silhouette a grazing entry leaves
    // nearly sideways past the floor while its neighbours land. Ended at
    // its exit it would end the beam there, and the floor between the rays
    // that land would go black (the ball lens before its focus: black
    // wedges between the rim's beams). It runs to the range instead; the
    // receiver test at each pixel still ends the beam at what it meets.
    if (r[0].len + r[1].len + r[2].len > 0.0)
        for (int i = 0; i < 3; i++)
            if (r[i].len <= 0.0)
                r[i].len = u_distance_range;
    for (int i = 0; i < 3; i++) {
        float dn = dot(r[i].d, n);
        if (dn < 0.05)
            return false; // an edge ray nearly across the beam's mean direction: not a beam to speak of
        back[i] = (dot(r[i].o, n) - plane) / dn; // how far back along the ray the base plane is
        v[i] = r[i].o - r[i].d * back[i];
        d[i] = r[i].d / dn;
        h[i] = max((r[i].len + back[i]) * dn, 0.0);
        top = max(top, h[i]);
    }
    float scale = max(max(distance(v[0], v[1]), distance(v[1], v[2])), distance(v[2], v[0]));
    // the area function A(y) = 0.5 |c0 + c1 y + c2 y^2| (Ernst et al. 2005)
    vec3 e1 = v[1] - v[0], e2 = v[2] - v[0], f1 = d[1] - d[0], f2 = d[2] - d[0];
    float c0 = dot(cross(e1, e2), n), c1 = dot(cross(e1, f2) + cross(f1, e2), n), c2 = dot(cross(f1, f2), n);
    float a0 = 0.5 * abs(c0);
    // the flux: the light-plane area of the triangle (intensity and weights per edge)
    vec2 l0 = lattice_plane(qa), l1 = lattice_plane(qb), l2 = lattice_plane(qc);
    vec2 el1 = l1 - l0, el2 = l2 - l0;
    float light_area = 0.5 * abs(el1.x * el2.y - el1.y * el2.x);
    // energy cut-off (§4.3): a beam ends where its flux density falls below
    // u_cutoff of its base's, or of the light's own where that is less (a
    // base near a focus is dense: cut at a fraction of its density, a beam
    // that focused inside the glass would not reach the floor it lights). Past both the vertex of the
    // quadratic and its larger root |A| only grows, so the cut is searched
    // there: a beam that only diverges from its base, as in the paper, and
    // one that spreads after a focus (a grazing entry at a silhouette
    // crosses the axis and fans out wide and faint: uncut, it filled the
    // fog's screen, 11.0 M fragments against 9.9 M cut).
    float light_ref = light_area;
    if (u_light_origin.w == 0.0) {
        // a point light's plane is at unit distance: its area at the base is D^2 times
        // (cos^3 of the ray off the axis left out: the reference only grows, the cut only moves out)
        vec3 middle = (v[0] + v[1] + v[2]) / 3.0;
        float dist = distance(u_light_origin.xyz, middle);
        light_ref *= dist * dist;
    }
    if (u_cutoff > 0.0 && a0 > 0.0) {
        float start = 0.0;
        if (c2 != 0.0) {
            float disc = c1 * c1 - 4.0 * c2 * c0;
            if (disc >= 0.0) {
                // the roots without cancellation (c2 -> 0 for near-parallel rays)
                float q = -0.5 * (c1 + (c1 >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
                start = max(start, q / c2);
                if (q != 0.0)
                    start = max(start, c0 / q);
            } else {
                start = max(start, -c1 / (2.0 * c2)); // no focus: |A| least at the vertex
            }
        } else if (c1 != 0.0) {
            start = max(start, -c0 / c1);
        } else {
            start = top; // a constant cross-section never thins out
        }
        float limit = max(a0, light_ref) / u_cutoff;
        float at_top = 0.5 * abs(c0 + c1 * top + c2 * top * top);
        if (start < top && at_top > limit) {
            float lo = start, hi = top;
            if (0.5 * abs(c0 + c1 * lo + c2 * lo * lo) > limit)
                hi = lo; // thinned out already where |A| starts to grow
            for (int it = 0; it < 16 && hi > lo; it++) {
                float m = 0.5 * (lo + hi);
                if (0.5 * abs(c0 + c1 * m + c2 * m * m) > limit)
                    hi = m;
                else
                    lo = m;
            }
            top = hi;
            for (int i = 0; i < 3; i++)
                h[i] = min(h[i], top);
        }
    }
    if (!(top > 1e-6 * max(scale, 1e-6)))
        return false;
    float a_top = 0.5 * abs(c0 + c1 * top + c2 * top * top);
    float a_floor = max(max(a0, a_top), 1e-30) / max(u_max_focus, 1.0);

    // the bounding volume
    vec3 t[3];
    for (int i = 0; i < 3; i++)
        t[i] = v[i] + d[i] * top;
    vec3 pts[6] = vec3[6](v[0], v[1], v[2], t[0], t[1], t[2]);
    float tol = 1e-4 * max(scale, top);
    bool prism = u_volumes == 1;
    uint diagonals = 0u;
    vec4 side[3]; // the touching plane of each base edge (for the prism)
    for (int e = 0; e < 3; e++) {
        int a = e, b = (e + 1) % 3, c = (e + 2) % 3;
        // base edge (a, b) with a top vertex; top edge (a', b') with a base vertex
        int base_pick = -1, base_count = 0, top_pick = -1, top_count = 0;
        float best = 1e30;
        for (int k = 0; k < 3; k++) {
            vec4 pl = plane_away(v[a], v[b], t[k], v[c]);
            float viol = violation(pl, pts);
            if (viol < best) {
                best = viol;
                side[e] = pl;
            }
            if (viol <= tol) {
                base_count++;
                base_pick = k;
            }
            vec4 pt = plane_away(t[a], t[b], v[k], t[c]);
            if (violation(pt, pts) <= tol) {
                top_count++;
                top_pick = k;
            }
        }
        // the side's two triangles must share a diagonal: (a, b, b') + (a', b', a) or (a, b, a') + (a', b', b)
        if (base_count != 1 || top_count != 1)
            prism = true;
        else if (base_pick == b && top_pick == a)
            diagonals |= 0u << e;
        else if (base_pick == a && top_pick == b)
            diagonals |= 1u << e;
        else
            prism = true;
    }
    if (prism) {
        // Ernst et al.'s prism: the three touching planes cut by the top plane y = top
        for (int i = 0; i < 3; i++) {
            vec3 u = cross(side[(i + 2) % 3].xyz, side[i].xyz); // the planes of the edges meeting at v[i]
            float un = dot(u, n);
            t[i] = abs(un) > 1e-8 ? v[i] + u * (top / un) : v[i] + d[i] * top;
        }
    }
    was_prism = prism;
    for (int i = 0; i < 3; i++) {
        bm.v[i] = vec4(v[i], h[i]);
        bm.d[i] = vec4(d[i], back[i]);
        bm.weight[i] = vec4(r[i].w, 0.0);
        bm.top[i] = vec4(t[i], 0.0);
    }
    bm.n = vec4(n, top);
    bm.area = vec4(c0, c1, c2, a_floor);
    bm.info = vec4(light_area, prism ? 1.0 : 0.0, float(diagonals), reflected ? 1.0 : 0.0);
    // the three rays left through the same interfaces; a beam across two media's boundary takes their mean
    bm.sigma = vec4((r[0].sigma + r[1].sigma + r[2].sigma) / 3.0, 0.0);
    bm.corners = uvec4(uint(vertex_index(qa.x, qa.y)), uint(vertex_index(qb.x, qb.y)), uint(vertex_index(qc.x, qc.y)), 0u);
    return true;
}

bool transmits(ivec2 q)
{
    return (uint(beam_vertices[vertex_index(q.x, q.y)].exit_pos.w + 0.5) & VERTEX_TRANSMITTED) != 0u;
}

// How many of a triangle's corners send their transmitted light where the
// camera sees it (0-3): its light-plane area counts that many thirds in the
// share the pass reports dropped. Light that leaves the view (water wider
// than it, the light a cube reflects inside and sends up) is not counted
// as lost: a sun 5 degrees over water 6 wide said 48% made no beam where
// none of the floor's light was missing.
uint seen_corners(ivec2 a, ivec2 b, ivec2 c)
{
    uint n = 0u;
    ivec2 q[3] = ivec2[3](a, b, c);
    for (int i = 0; i < 3; i++)
        n += (uint(beam_vertices[vertex_index(q[i].x, q[i].y)].exit_pos.w + 0.5) & VERTEX_SEEN) != 0u ? 1u : 0u;
    return n;
}

bool whole(ivec2 a, ivec2 b, ivec2 c, bool reflected)
{
    Ray ra = vertex_ray(a.x, a.y, reflected), rb = vertex_ray(b.x, b.y, reflected), rc = vertex_ray(c.x, c.y, reflected);
    if (!(ray_ok(ra, reflected) && ray_ok(rb, reflected) && ray_ok(rc, reflected) &&
          ra.signature == rb.signature && rb.signature == rc.signature))
        return false;
    uint snapped = (ra.flags | rb.flags | rc.flags) & VERTEX_SNAPPED;
    if (snapped == 0u)
        return true;
    // A corner moved onto the silhouette: not all three (the cell is off the
    // refractors), and not where the move turned the triangle over on the
    // light's plane (it would light again what its neighbours light). Its
    // ray may enter grazing and leave bent hard, far from the others' way:
    // a wide, faint beam, kept all the same (it lights the floor between
    // the rim's beams of a ball before its focus, which went black when
    // such cells were dropped; the energy cut-off bounds it).
    if (((ra.flags & rb.flags & rc.flags) & VERTEX_SNAPPED) != 0u)
        return false;
    vec2 la = lattice_plane(a), lb = lattice_plane(b), lc = lattice_plane(c);
    vec2 ga = vec2(b - a), gc = vec2(c - a);
    float moved = (lb.x - la.x) * (lc.y - la.y) - (lb.y - la.y) * (lc.x - la.x);
    return moved * (ga.x * gc.y - ga.y * gc.x) > 0.0;
}

void main()
{
    uint k = gl_GlobalInvocationID.x;
    // up to four beams a cell: two triangles, transmitted and reflected
    Beam made[4];
    int count = 0, prisms = 0;
    uint whole_area = 0u, parted_area = 0u;
    if (k < counters[COUNT_KEPT]) {
        int level, x, y;
        cell_unpack(cells[u_kept_offset + int(k)], level, x, y);
        int step = 1 << (u_refine - level);
        ivec2 q[4] = ivec2[4](ivec2(x, y) * step, ivec2(x + 1, y) * step, ivec2(x + 1, y + 1) * step,
                              ivec2(x, y + 1) * step);
        for (int kind = 0; kind < 2; kind++) {
            bool reflected = kind == 1;
            if (reflected && u_reflection == 0)
                break;
            // the diagonal that keeps more triangles whole
            bool t0 = whole(q[0], q[1], q[2], reflected), t1 = whole(q[0], q[2], q[3], reflected);
            bool t2 = whole(q[0], q[1], q[3], reflected), t3 = whole(q[1], q[2], q[3], reflected);
            bool first = int(t0) + int(t1) >= int(t2) + int(t3);
            ivec3 pair[2] = first ? ivec3[2](ivec3(0, 1, 2), ivec3(0, 2, 3)) : ivec3[2](ivec3(0, 1, 3), ivec3(1, 2, 3));
            bool kept[2] = first ? bool[2](t0, t1) : bool[2](t2, t3);
            ivec2 tri[6];
            int ntri = 0;
            for (int i = 0; i < 2; i++) {
                ivec3 c = pair[i];
                if (kept[i]) {
                    tri[3 * ntri] = q[c.x];
                    tri[3 * ntri + 1] = q[c.y];
                    tri[3 * ntri + 2] = q[c.z];
                    ntri++;
                    whole_area += reflected ? 0u : uint(step * step) * seen_corners(q[c.x], q[c.y], q[c.z]);
                } else if (!reflected && transmits(q[c.x]) && transmits(q[c.y]) && transmits(q[c.z])) {
                    // light this cell drops: its corners all pass light through
                    // but not the same way (leave by different faces, or one
                    // totally reflected)
                    parted_area += uint(step * step) * seen_corners(q[c.x], q[c.y], q[c.z]);
                }
            }
            for (int i = 0; i < ntri; i++) {
                bool prism;
                if (make_beam(tri[3 * i], tri[3 * i + 1], tri[3 * i + 2], reflected, made[count], prism)) {
                    prisms += prism ? 1 : 0;
                    count++;
                }
            }
        }
    }
    // the appends in uniform control flow: every invocation adds (perhaps 0)
    uint at = atomicAdd(counters[COUNT_BEAMS], uint(count));
    atomicAdd(counters[COUNT_PRISMS], uint(prisms));
    atomicAdd(counters[COUNT_WHOLE], whole_area);
    atomicAdd(counters[COUNT_PARTED], parted_area);
    for (int i = 0; i < count; i++) {
        if (at + uint(i) >= uint(u_beam_capacity)) {
            atomicAdd(counters[COUNT_OVERFLOW], 1u);
            break;
        }
        beams[at + uint(i)] = made[i];
        for (int k = 0; k < 3; k++) {
            uint v = made[i].corners[k];
            uint slot = atomicAdd(adjacency[v * uint(ADJACENCY_STRIDE)], 1u);
            if (slot < uint(ADJACENCY_SLOTS))
                adjacency[v * uint(ADJACENCY_STRIDE) + 1u + slot] = at + uint(i);
        }
    }
}
