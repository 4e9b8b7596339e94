// Liktor & Dachsbacher 2011: the data the stages of beam_caustics share
// (src/passes/techniques/beam_caustics.c mirrors the layouts and counter offsets).

// One vertex of the finest lattice of the light's projected grid (§4.1):
// the edge rays of every beam that has it as a corner, traced once.
struct BeamVertex {
    vec4 exit_pos;   // transmitted ray: where it leaves the last interface (world), w = flags
    vec4 exit_dir;   // its direction (unit), w = its extrusion length (distance to the receivers)
    vec4 exit_weight;// its flux weight (Fresnel, absorption, spot, medium before the glass), w = path signature
    vec4 refl_pos;   // reflected ray: the first interface's point, w = the first layer's eye depth
    vec4 refl_dir;   // its direction, w = extrusion length
    vec4 refl_weight;// Fresnel reflectance x the rest, w = unused
    vec4 normal;     // the first interface's normal (world), w = unused
    vec4 light_plane;// xy: the vertex on the light's image plane (world units, or tangents for a point/spot light)
    vec4 exit_sigma; // rgb: absorption per unit length of the medium the transmitted ray leaves into (an open
                     // one, water: no layer below it, the receivers are inside it), 0 outside every refractor
};

const uint VERTEX_TRANSMITTED = 1u, VERTEX_REFLECTED = 2u, VERTEX_SURFACE = 4u;
// The vertex's own texel misses the refractors and its rays were traced from
// the nearest texel towards a neighbour that meets them (the silhouette): a
// beam needs at least one corner that is not snapped.
const uint VERTEX_SNAPPED = 8u;
// Its transmitted ray meets a receiver (or the medium) inside the camera's
// view: the light the pass counts when it says how much makes no beam.
const uint VERTEX_SEEN = 16u;

layout(std430) buffer BeamVertices { BeamVertex beam_vertices[]; };

// A beam (§4.3): base triangle v[i] (world), edge directions d[i] scaled so
// that dot(d, n) = 1 (Ernst et al. 2005's beam space: y along n), the area
// function A(y) = 0.5 |c0 + c1 y + c2 y^2| of its cross-section parallel
// to the base, and its bounding volume's top corners at height n.w.
struct Beam {
    vec4 v[3];       // w: the edge's end height (extrusion) in beam space
    vec4 d[3];       // w: how far the base lies behind the ray's exit along the ray (nothing is absorbed there)
    vec4 weight[3];  // per edge: flux per unit light-plane area (rgb)
    vec4 n;          // unit normal of the base, w = the bounding volume's top height
    vec4 area;       // c0, c1, c2, w = the floor |A| is clamped to (a focus stays finite)
    vec4 info;       // x = light-plane area x intensity scale, y = 1 prism / 0 tight, z = diagonal bits, w = 1 reflected
    vec4 top[3];     // the bounding volume's top corners (world)
    uvec4 corners;   // xyz: its lattice vertices (their adjacency lists), w: unused
    vec4 sigma;      // rgb: absorption per unit length along the edge rays (the medium the beam runs in)
};

layout(std430) buffer Beams { Beam beams[]; };

// Per lattice vertex, the beams that have it as a corner: a count, then up
// to ADJACENCY_SLOTS beam indices (the lattice's adjacency, which lets the
// surface caustics interpolate a flux density per edge ray, Ernst et al.
// 2005, instead of one per beam: §7's limitation).
const int ADJACENCY_STRIDE = 16, ADJACENCY_SLOTS = 15;
layout(std430) buffer BeamAdjacency { uint adjacency[]; };

// Counters and indirect arguments (uint offsets).
const int COUNT_DISPATCH = 0;   // x, y, z: the current cell list's dispatch
const int COUNT_IN = 3;         // cells in the current list
const int COUNT_NEXT = 4;       // cells appended to the next list
const int COUNT_KEPT = 5;       // cells kept as beams' bases
const int COUNT_BEAMS = 6;      // beams built
const int COUNT_DRAW = 8;       // count, instances, first, base instance
const int COUNT_BUILD = 12;     // x, y, z: the beam builder's dispatch
const int COUNT_OVERFLOW = 15;  // cells or beams past capacity (dropped)
const int COUNT_PRISMS = 16;    // beams that fell back to the prism
const int COUNT_WHOLE = 17;     // light-plane area (lattice units) x corners seen of transmitted triangles made beams
const int COUNT_PARTED = 18;    // ... of triangles lit at every corner whose paths part (no beam)
const int COUNT_SIZE = 20;
layout(std430) buffer BeamCounters { uint counters[]; };

// Cells of the refinement: level (bits 28-31), x (14 bits), y (14 bits).
layout(std430) buffer BeamCells { uint cells[]; };
uint cell_pack(int level, int x, int y) { return (uint(level) << 28) | (uint(x) << 14) | uint(y); }
void cell_unpack(uint c, out int level, out int x, out int y)
{
    level = int(c >> 28);
    x = int((c >> 14) & 0x3fffu);
    y = int(c & 0x3fffu);
}

// The pass's values for one frame, every stage's (issue 54): one block,
// uploaded in one call, mirrored by struct beam_params in
// src/passes/techniques/beam_caustics.c (gl_param_block holds the two to
// each other). What changes between dispatches (a level's offsets, the
// advance's mode, the filter's direction) stays a plain uniform.
layout(std140) uniform BeamParams {
    vec4 u_light_origin;    // xyz: a point light's position; w = 1: a directional light (no position)
    vec3 u_distance_center; // the receivers' distance impostor's centre (distance.glsl)
    float u_distance_range; // the longest an edge ray is traced
    vec2 u_jitter;          // the lattice's offset this frame, in lattice cells (within +-0.5; issue 32)
    int u_lattice;          // M: cells of the finest lattice per side (grid x 2^refine)
    int u_refine;           // levels of the lattice below the coarse grid (refine + edges)
    int u_capacity;         // cells one list holds
    int u_beam_capacity;    // beams the buffer holds
    int u_kept_offset;      // where the kept cells' list starts
    int u_light;            // the light's entry in the frame's list
    int u_light_ortho;      // a directional light: parallel edge rays
    int u_free;             // levels below this split on every criterion; the rest on silhouettes only
    int u_reflection;       // beams reflected off the first interface too (§6)
    int u_volumes;          // 0: tight (falling back to the prism), 1: the prism always
    int u_samples;          // samples along a view ray's interval in a beam (1: the paper's midpoint)
    int u_surface;          // surface caustics too
    int u_smooth;           // surface caustics from a density per edge ray, averaged over the beams sharing it
    float u_focus;          // split when min A(y) / A(0) along the beam falls below this
    float u_pixels;         // split when the beam's width on screen exceeds this many pixels
    float u_normal_cos;     // split when two corners' normals differ more than this (cosine)
    float u_depth_jump;     // split when two corners' depths differ more than this x the cell's side
    float u_cutoff;         // a beam ends where its flux density is below this fraction of its base's or the light's
    float u_max_focus;      // the bound on focusing: |A| >= A_max / u_max_focus
};

int vertex_index(int i, int j) { return j * (u_lattice + 1) + i; }
