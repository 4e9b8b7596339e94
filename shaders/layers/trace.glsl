// Image-space ray tracing through every depth layer (Chaudhari 2008,
// §3.6-3.8, after Oliveira & Brauwers 2007): from the first layer of a
// pixel, at each interface a search along the ray for where it crosses
// the next layer in its direction, Snell's law there (or total internal
// reflection, which the thesis leaves out: the ray then searches the layer
// before it, §4.3's suggestion), Beer-Lambert absorption over the length
// inside, until no layer is left in the ray's direction. All in the eye
// space of the view the layers were taken from.
//
// Departures from the thesis, each measured in the README's bench:
// - The search first steps linearly (u_steps) to the first sample beyond
//   the layer, then bisects (u_search, the thesis's 5): a bisection alone
//   can converge on any crossing of a concave layer, not the first.
// - A crossing is kept only where the layer exists on both sides of it; a
//   ray that leaves a layer's footprint (a silhouette) has left the object
//   there, the thesis's "false intersections" of §4.3.
// - Whether an interface is entered or left comes from the mesh normal's
//   side, not the layer's parity, so two surfaces merged into one voxel
//   (a lost pair of layers) do not turn inside and outside around.
// - Optical path length is the geometric one (§3.8 multiplies by eta; the
//   reference's absorption is per unit length, as Fig. 4.4's caption says).
#include "layers/layers.glsl"
#include "common/fresnel.glsl"
uniform sampler2DArray u_layer_depth;
uniform sampler2DArray u_layer_normal;
uniform usampler2D u_layer_info;
layout(std430) readonly buffer LayerRanges { uint layer_ranges[]; };
struct LayerMaterial {
    vec4 ior_ideal;  // x = ior, y = 1 for an ideal interface
    vec4 absorption; // rgb per unit length
};
layout(std430) readonly buffer LayerMaterials { LayerMaterial layer_materials[]; };
// (u_layer_inv_view, u_layer_inv_proj, u_layer_size: layers.glsl's LayerView)
uniform int u_search;       // bisection steps per interface (§3.6: 5)
uniform int u_steps;        // linear steps before them
uniform int u_gradient;     // 0: the mesh normals; d > 0: eq. 3.2's perspective-corrected gradient with delta = d
uniform int u_max_interfaces;
uniform float u_layer_extent; // the longest a segment inside the layers can be (the refractors' bounding diameter)

const int LAYER_MAX_INTERFACES = 66;

struct LayerPath {
    bool entered;     // the pixel has a layer (the ray met a refractor)
    vec3 origin;      // where the ray leaves the last interface (eye space)
    vec3 dir;         // and its direction
    vec3 throughput;  // Fresnel transmission after the first interface, and absorption
    float fresnel0;   // reflectance at the first interface (1 under total internal reflection)
    vec3 normal0;     // the first interface's normal, facing the incoming ray
    vec3 entry;       // the first interface's point
    int interfaces;   // interfaces crossed or reflected at
    int tir;          // total internal reflections met
    bool capped;      // stopped by the interface cap, not by leaving
    int medium;       // the refractor slot the ray is inside when it leaves (-1: outside every one):
                      // an open surface (water) has no layer below it, so its ray is still in the medium
    // The part reflected back inside where the path first left a refractor
    // through an interface that also reflects (Fresnel): where, which way,
    // its share of the light, and the medium and layer gap it stays in, for
    // a second march (layer_continue). The thesis drops it (§3.8); at an
    // exit just past a total internal reflection it is most of the light.
    // Only where the includer defines LAYER_TRACE_SPLIT (layered_refraction):
    // the photons' and beams' shaders do not carry it.
    bool split;
#ifdef LAYER_TRACE_SPLIT
    vec3 split_origin, split_dir, split_weight;
    int split_medium, split_gap, split_interfaces;
#endif
};

// Beer-Lambert over a length t inside the path's last medium: the rest of
// the way to a receiver inside an open medium (water over a floor), which no
// layer bounds; nothing outside every refractor.
vec3 layer_path_sigma(LayerPath path)
{
    return path.medium >= 0 ? layer_materials[path.medium].absorption.rgb : vec3(0.0);
}

vec3 layer_path_absorption(LayerPath path, float t) { return exp(-layer_path_sigma(path) * max(t, 0.0)); }

int layer_count(ivec2 q)
{
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_layer_size)))
        return 0;
    return int(texelFetch(u_layer_info, q, 0).r);
}

float layer_depth(ivec2 q, int k) { return texelFetch(u_layer_depth, ivec3(q, k), 0).r; }

int layer_slot(ivec2 q, int k) { return int(texelFetch(u_layer_normal, ivec3(q, k), 0).w + 0.5) - 1; }

// The eye-space point of pixel position `px` (in pixels) at eye depth d.
vec3 layer_point(vec2 px, float d)
{
    vec2 ndc = px / vec2(u_layer_size) * 2.0 - 1.0;
    vec4 a = u_layer_inv_proj * vec4(ndc, -1.0, 1.0);
    vec4 b = u_layer_inv_proj * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w, dir = b.xyz / b.w - o;
    float t = (d + o.z) / (abs(dir.z) > 1e-30 ? -dir.z : -1e-30);
    return o + dir * t;
}

vec2 layer_pixel(vec3 pe)
{
    vec4 c = u_layer_proj * vec4(pe, 1.0);
    return (c.xy / max(c.w, 1e-30) * 0.5 + 0.5) * vec2(u_layer_size);
}

// The mesh normal of layer k at q in eye space (unit), or with u_gradient
// eq. 3.2: the cross product of central differences of the layer's points
// delta pixels apart (one-sided where a neighbour has no such layer),
// turned to the mesh normal's side.
vec3 layer_normal(ivec2 q, int k)
{
    vec3 n = mat3(u_layer_view) * texelFetch(u_layer_normal, ivec3(q, k), 0).xyz;
    if (u_gradient > 0) {
        vec3 c = layer_point(vec2(q) + 0.5, layer_depth(q, k));
        vec3 p[4];
        ivec2 off[4] = ivec2[4](ivec2(u_gradient, 0), ivec2(-u_gradient, 0), ivec2(0, u_gradient), ivec2(0, -u_gradient));
        for (int i = 0; i < 4; i++) {
            ivec2 s = q + off[i];
            p[i] = layer_count(s) > k ? layer_point(vec2(s) + 0.5, layer_depth(s, k)) : c;
        }
        vec3 g = cross(p[0] - p[1], p[2] - p[3]);
        if (dot(g, g) > 1e-30) {
            g = normalize(g);
            n = dot(g, n) < 0.0 ? -g : g;
        }
    }
    float len = length(n);
    return len > 1e-20 ? n / len : vec3(0.0, 0.0, 1.0);
}

// Layer k's depth and normal at a continuous pixel position: bilinear over
// the four texels around it that have layer k on the same surface (depth
// within 2% of the layers' extent of the nearest texel's), so neither the
// crossing nor the normal snaps to the texel grid (§3.4.2 filters the
// depth images in hardware for the same reason). `exists`: the nearest
// texel has layer k.
float layer_depth_at(vec2 px, int k, out bool exists)
{
    ivec2 q = ivec2(floor(px));
    exists = layer_count(q) > k;
    if (!exists)
        return 0.0;
    float near_d = layer_depth(q, k);
    vec2 f = px - 0.5;
    ivec2 c = ivec2(floor(f));
    vec2 t = f - vec2(c);
    float sum = 0.0, wsum = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 s = c + ivec2(i, j);
            if (layer_count(s) <= k)
                continue;
            float d = layer_depth(s, k);
            if (abs(d - near_d) > 0.02 * u_layer_extent)
                continue;
            float w = (i == 1 ? t.x : 1.0 - t.x) * (j == 1 ? t.y : 1.0 - t.y);
            sum += w * d;
            wsum += w;
        }
    return wsum > 1e-6 ? sum / wsum : near_d;
}

vec3 layer_normal_at(vec2 px, int k)
{
    ivec2 q = ivec2(floor(px));
    if (u_gradient > 0 || layer_count(q) <= k)
        return layer_normal(q, k);
    float near_d = layer_depth(q, k);
    vec2 f = px - 0.5;
    ivec2 c = ivec2(floor(f));
    vec2 t = f - vec2(c);
    vec3 near_n = layer_normal(q, k);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            ivec2 s = c + ivec2(i, j);
            if (layer_count(s) <= k || abs(layer_depth(s, k) - near_d) > 0.02 * u_layer_extent)
                continue;
            vec3 n = mat3(u_layer_view) * texelFetch(u_layer_normal, ivec3(s, k), 0).xyz;
            // across an edge of a faceted object (normals ~25 degrees or
            // more apart) the nearest texel's own normal, as
            // common/surface_normal.glsl does: a blend there is a normal
            // of neither face, and a path near the critical angle turns
            // the wrong way along the edge (issue 52, case 12: bands of
            // wrong pixels along the TIR cube's vertical edges)
            if (dot(normalize(n), near_n) < 0.9)
                return near_n;
            float w = (i == 1 ? t.x : 1.0 - t.x) * (j == 1 ? t.y : 1.0 - t.y);
            sum += w * n;
        }
    float len = length(sum);
    return len > 1e-12 ? sum / len : near_n;
}

float layer_range(int k, bool upper) { return uintBitsToFloat(layer_ranges[2 * k + (upper ? 1 : 0)]); }

// Is the ray point at eye position pe past layer k (deeper: behind it;
// else: in front of it)? Where the pixel has no such layer the ray is past
// it too (it cannot meet what is not there). `exists` says which.
bool beyond(vec3 pe, int k, bool deeper, out bool exists, out vec2 q)
{
    q = layer_pixel(pe);
    float l = layer_depth_at(q, k, exists);
    if (!exists)
        return true;
    float d = -pe.z;
    return deeper ? d >= l : d <= l;
}

// The first crossing of layer k from o along d, within t_end: its ray
// parameter and pixel; false where the ray leaves the layer's footprint or
// the image instead.
bool layer_search(vec3 o, vec3 d, int k, bool deeper, float t_end, bool probe, out float t_hit, out vec2 q_hit)
{
    float lo = 0.0, hi = -1.0;
    bool exists;
    vec2 q;
    int steps = max(u_steps, 1);
    // With `probe` (the ray has just entered a refractor), three short
    // probes first, at an eighth, a quarter and a half of the first step:
    // the far side of a thin wall (a wine glass's 0.012 against a step of
    // t_end / 8, t_end the layer's whole depth range) lies within the first
    // step, whose sample then lands past the wall's footprint and ends the
    // path there (issue 52, case 15: fan-shaped streaks, 0.386 from the
    // reference; 0.076 with them). Steps that grow throughout (quadratic),
    // or the probes after every interface, cost thick objects' paths after
    // a total internal reflection their accuracy (the IOR-2.42 cube seen
    // through layered_refraction: 1,150 -> 765 pixels within 0.02).
    for (int j = probe ? -2 : 1; j <= steps; j++) {
        float t = j > 0 ? t_end * float(j) / float(steps) : t_end / float(steps) * exp2(float(j) - 1.0);
        if (beyond(o + d * t, k, deeper, exists, q)) {
            hi = t;
            break;
        }
        lo = t;
    }
    if (hi < 0.0)
        return false;
    for (int i = 0; i < u_search; i++) {
        float mid = 0.5 * (lo + hi);
        if (beyond(o + d * mid, k, deeper, exists, q))
            hi = mid;
        else
            lo = mid;
    }
    // a real crossing has the layer on its far side too
    beyond(o + d * hi, k, deeper, exists, q);
    if (!exists)
        return false;
    t_hit = hi;
    q_hit = q;
    return true;
}

// Snell's law at an interface of refractor `slot` with normal n (eye space,
// either side); updates the medium. False under total internal reflection
// (d is then reflected).
bool layer_interface(inout vec3 d, vec3 n, int slot, inout int medium, out float fresnel, out vec3 facing)
{
    int s = clamp(slot >= 0 ? slot : max(medium, 0), 0, 63);
    bool entering = dot(n, d) < 0.0;
    float ior = layer_materials[entering ? s : (medium >= 0 ? medium : s)].ior_ideal.x;
    float ideal = layer_materials[entering ? s : (medium >= 0 ? medium : s)].ior_ideal.y;
    float eta = entering ? 1.0 / ior : ior;
    facing = entering ? n : -n;
    vec3 t = refract(d, facing, eta);
    if (dot(t, t) == 0.0) {
        fresnel = 1.0;
        d = reflect(d, facing);
        return false;
    }
    fresnel = fresnel_of(-dot(d, facing), eta, ideal);
    d = normalize(t);
    medium = entering ? s : -1;
    return true;
}

// A path before its first interface.
LayerPath layer_path_start()
{
    LayerPath path;
    path.entered = false;
    path.throughput = vec3(1.0);
    path.interfaces = 0;
    path.tir = 0;
    path.capped = false;
    path.fresnel0 = 0.0;
    path.medium = -1;
    path.split = false;
    return path;
}

// The rest of a path from P along d, inside `medium` (-1: none) between
// layers gap and gap + 1, until no layer is left in its direction. With
// `split`, the first exit that also reflects records the reflected part.
void layer_march(inout LayerPath path, vec3 P, vec3 d, int medium, int gap, bool split)
{
    float f;
    vec3 facing;
    int max_count = int(layer_ranges[2 * 32]);
    int cap = min(u_max_interfaces, LAYER_MAX_INTERFACES);
    // the ray has just come in through a refractor's surface (the path's
    // first interface, or a later one from outside): layer_search probes
    // close ahead for a thin wall's far side
    bool entered_last = medium >= 0 && path.interfaces == 1;
    for (int i = 0; i < LAYER_MAX_INTERFACES; i++) {
        if (path.interfaces >= cap) {
            path.capped = true;
            break;
        }
        bool deeper = d.z < 0.0;
        int k = deeper ? gap + 1 : gap;
        if (k < 0 || k >= max_count)
            break;
        // how far along d until the eye depth passes the layer's range
        float rate = -d.z, t_end = u_layer_extent;
        float bound = deeper ? layer_range(k, true) * 1.001 + 1e-4 : layer_range(k, false) * 0.999 - 1e-4;
        if (abs(rate) > 1e-6)
            t_end = clamp((bound + P.z) / rate, 0.0, u_layer_extent);
        float t;
        vec2 q;
        if (t_end <= 0.0 || !layer_search(P, d, k, deeper, t_end, entered_last, t, q))
            break;
        vec3 H = P + d * t;
        if (medium >= 0)
            path.throughput *= exp(-layer_materials[medium].absorption.rgb * t);
        P = H;
        vec3 d_in = d;
        int medium_in = medium, gap_in = gap;
        bool refracted = layer_interface(d, layer_normal_at(q, k), layer_slot(ivec2(floor(q)), k), medium, f, facing);
        path.interfaces++;
        entered_last = refracted && medium_in < 0 && medium >= 0;
        if (refracted) {
#ifdef LAYER_TRACE_SPLIT
            if (split && !path.split && medium_in >= 0 && medium < 0 && f > 0.0) {
                path.split = true;
                path.split_origin = H;
                path.split_dir = reflect(d_in, facing);
                path.split_weight = path.throughput * f;
                path.split_medium = medium_in;
                path.split_gap = gap_in;
                path.split_interfaces = path.interfaces;
            }
#endif
            path.throughput *= 1.0 - f;
            gap = deeper ? k : k - 1;
        } else {
            path.tir++;
        }
        // step off the surface so the next search starts on its far side
        P += d * (1e-4 * u_layer_extent);
    }
    path.origin = P;
    path.dir = d;
    path.medium = medium;
}

// The path of the ray `d0` (eye space) that meets the first layer at the
// continuous pixel position `px` (in pixels; inside a texel that has a
// layer): its depth and normal interpolated over the texels of the same
// surface (layer_depth_at). At a texel's centre that is the texel's own
// depth and normal, exactly; a caustics pass that jitters its photons or
// beams within their texels (issue 32's temporal accumulation) starts them
// off the centre.
LayerPath layer_trace_at(vec2 px, vec3 d0)
{
    LayerPath path = layer_path_start();
    ivec2 p = ivec2(floor(px));
    bool exists;
    float depth = layer_depth_at(px, 0, exists);
    if (!exists)
        return path;
    path.entered = true;
    vec3 P = layer_point(px, depth);
    vec3 d = normalize(d0);
    int medium = -1;
    float f;
    vec3 facing;
    bool through = layer_interface(d, layer_normal_at(px, 0), layer_slot(p, 0), medium, f, facing);
    path.fresnel0 = f;
    path.normal0 = facing;
    path.entry = P;
    path.interfaces = 1;
    if (through) {
        layer_march(path, P, d, medium, 0, true);
    } else { // total reflection at the first interface: nothing enters (the reflection term, not an internal one)
        path.origin = P;
        path.dir = d;
        path.medium = medium;
    }
    return path;
}

// The path of the ray `d0` (eye space) that meets pixel p's first layer.
LayerPath layer_trace(ivec2 p, vec3 d0) { return layer_trace_at(vec2(p) + 0.5, d0); }

#ifdef LAYER_TRACE_SPLIT
// The next march: the part `path` reflected back inside where it first
// left, followed from there on its own (its throughput starts at that
// part's share), itself recording where it first leaves.
LayerPath layer_continue(LayerPath from)
{
    LayerPath path = layer_path_start();
    path.entered = true;
    path.throughput = from.split_weight;
    path.interfaces = from.split_interfaces;
    path.fresnel0 = from.fresnel0;
    path.normal0 = from.normal0;
    path.entry = from.entry;
    layer_march(path, from.split_origin + from.split_dir * (1e-4 * u_layer_extent), from.split_dir, from.split_medium,
                from.split_gap, true);
    return path;
}
#endif
