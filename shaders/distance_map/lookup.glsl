#include "common/scene_bounds.glsl"
// What a ray sees in the distance map (src/passes/blocks/distance_map.h,
// Szirmay-Kalos et al. 2005): the ray is walked in steps spread in the
// angle seen from the map's centre (t = 4 s a / (1 - a) for a evenly
// spaced in [0, 1), s the origin's distance from the centre), each point
// compared with the distances stored in its direction; between the last
// point in front of a stored surface and the first behind it a false
// position search finds the hit. A crossing where the stored distance
// jumps (an edge seen from the centre, the ray passing behind the nearer
// object) keeps a large gap after the search: no hit there. Behind layer
// 0's surface the ray looks for layer 1's (the surface facing the centre
// beyond it: the wall beside a box).
uniform samplerCube u_distance_color;
uniform samplerCube u_distance_distance;
uniform samplerCube u_distance_color_behind;
uniform samplerCube u_distance_distance_behind;
uniform vec3 u_distance_center;
uniform int u_distance_steps = 24;

// |p - c| minus the stored distance of `layer` in p's direction: < 0 in
// front of that surface, >= 0 behind it (very negative: none stored)
float distance_map_gap(vec3 p, int layer)
{
    vec3 d = p - u_distance_center;
    return length(d) - (layer == 0 ? texture(u_distance_distance, d).r : texture(u_distance_distance_behind, d).r);
}

// False position between t0 (in front, g0 < 0) and t1 (behind), Illinois
// style (the weight of the end that stays put is halved). True with the
// hit's t when the gap closes there (a surface, not a jump).
bool distance_map_refine(vec3 o, vec3 d, int layer, float t0, float g0, float t1, float g1, out float t_hit)
{
    float lo = t0, hi = t1, wlo = g0, whi = g1;
    float best_t = t1, best_g = g1;
    int side = 0;
    for (int k = 0; k < 10; k++) {
        float t = lo + (hi - lo) * wlo / (wlo - whi);
        float g = distance_map_gap(o + t * d, layer);
        if (abs(g) < abs(best_g)) {
            best_g = g;
            best_t = t;
        }
        if (g < 0.0) {
            lo = t;
            wlo = g;
            if (side == -1)
                whi *= 0.5;
            side = -1;
        } else {
            hi = t;
            whi = g;
            if (side == 1)
                wlo *= 0.5;
            side = 1;
        }
    }
    t_hit = best_t;
    return abs(best_g) < 0.02 * length(o + best_t * d - u_distance_center) + 1e-4;
}

bool distance_map_lookup(vec3 o, vec3 d, int steps, out vec3 color)
{
    color = vec3(0.0);
    // nothing to find outside the diffuse objects' box (common/scene_bounds.glsl)
    float t_enter, t_exit;
    if (!scene_bounds_segment(o, d, t_enter, t_exit))
        return false;
    float s = max(length(o - u_distance_center), 1e-3);
    float t0 = 0.0, a0 = distance_map_gap(o, 0), b0 = distance_map_gap(o, 1);
    steps = clamp(steps, 4, 256);
    for (int i = 1; i <= steps + 1; i++) {
        float a = float(i) / float(steps + 1);
        // t = s at a = 0.2: most steps past the refractor, where the walls
        // are; the last step far beyond anything (a miss: the environment)
        if (t0 > t_exit)
            return false;
        float t1 = i > steps ? 1e6 * s : s * a / (1.0 - a) * 4.0;
        vec3 p1 = o + t1 * d;
        float a1 = distance_map_gap(p1, 0), b1 = distance_map_gap(p1, 1);
        float t_hit;
        if (a0 < 0.0 && a1 >= 0.0 && distance_map_refine(o, d, 0, t0, a0, t1, a1, t_hit)) {
            color = texture(u_distance_color, o + t_hit * d - u_distance_center).rgb;
            return true;
        }
        // behind layer 0 (hidden from the centre): layer 1's surface
        if (a1 >= 0.0 && b0 < 0.0 && b1 >= 0.0 && distance_map_refine(o, d, 1, t0, b0, t1, b1, t_hit)) {
            color = texture(u_distance_color_behind, o + t_hit * d - u_distance_center).rgb;
            return true;
        }
        t0 = t1;
        a0 = a1;
        b0 = b1;
    }
    return false;
}
