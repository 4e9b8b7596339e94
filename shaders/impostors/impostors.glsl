// The impostors' frames (src/passes/blocks/impostors.h) and the ray lookup of Hu &
// Qin §2.2: intersect a ray with the rectangles, then correct the hit with
// the depth texture (the iterative lookup of Fig. 16).
struct Impostor {
    vec4 center; // xyz, w = half side d_i
    vec4 axis;
    vec4 right;
    vec4 up;
};
layout(std430) readonly buffer Impostors { Impostor impostors[]; };
uniform sampler2DArray u_impostor_depth;
uniform sampler2DArray u_impostor_color;
uniform int u_impostor_count;
uniform int u_skip_impostor = -1; // the object being shaded does not see its own impostor

vec2 impostor_uv(int k, vec3 p)
{
    Impostor im = impostors[k];
    vec3 d = p - im.center.xyz;
    return vec2(dot(d, im.right.xyz), dot(d, im.up.xyz)) / (2.0 * im.center.w) + 0.5;
}

float impostor_depth(int k, vec2 uv)
{
    return texture(u_impostor_depth, vec3(uv, float(k))).r;
}

// The surface point impostor k stores at uv (the inverse of impostor_uv).
vec3 impostor_point(int k, vec2 uv)
{
    Impostor im = impostors[k];
    vec2 s = (uv - 0.5) * 2.0 * im.center.w;
    return im.center.xyz + im.right.xyz * s.x + im.up.xyz * s.y + im.axis.xyz * impostor_depth(k, uv);
}

// The depth stored at uv, 1e30 (no surface) outside the impostor.
float impostor_depth_inside(int k, vec2 uv)
{
    return any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) ? 1e30 : impostor_depth(k, uv);
}

// Where does the ray (o, d) meet the object of impostor k? Hu & Qin §2.2.2:
// the seed matters. Candidates are the ray's points at the rectangle
// (P_rect) and at the front and back of the impostor's slab; a candidate
// "beyond" the surface stored at its own texel (its z past P_select's) is
// preferred, the one closest to that surface among them; failing that,
// the candidate with the closest z. Then `iterations` times: look up the
// depth at the current texel and move along the ray to that depth (Fig.
// 16). Returns the distance t (or -1 for a miss) and the texel uv.
float impostor_hit(int k, vec3 o, vec3 d, int iterations, out vec2 uv)
{
    Impostor im = impostors[k];
    float along = dot(d, im.axis.xyz);
    uv = vec2(0.0);
    if (abs(along) < 1e-4)
        return -1.0; // the rectangle seen edge-on: no hit (never a division by ~0)
    float base = dot(im.center.xyz - o, im.axis.xyz);
    float half_side = im.center.w;
    float best_t = -1.0, best_gap = 1e30, fallback_t = -1.0, fallback_gap = 1e30;
    // no iterations: the uncorrected lookup at P_rect (Fig. 18c)
    for (int c = -1; c <= 1 && iterations > 0; c++) {
        float z = float(c) * half_side;      // depth of the candidate along the axis
        float t = (base + z) / along;
        if (t <= 0.0)
            continue;
        vec2 cuv = impostor_uv(k, o + t * d);
        if (any(lessThan(cuv, vec2(0.0))) || any(greaterThan(cuv, vec2(1.0))))
            continue;
        float surface = impostor_depth(k, cuv);
        if (surface >= 1e29)
            continue;
        float gap = abs(z - surface);
        if (z >= surface && gap < best_gap) {
            best_gap = gap;
            best_t = t;
        }
        if (gap < fallback_gap) {
            fallback_gap = gap;
            fallback_t = t;
        }
    }
    float t = best_t > 0.0 ? best_t : fallback_t;
    if (t <= 0.0) {
        // no candidate sees the object: the plain rectangle hit, if any
        t = base / along;
        if (t <= 0.0)
            return -1.0;
    }
    uv = impostor_uv(k, o + t * d);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return -1.0;
    for (int i = 0; i < iterations; i++) { // capped by the caller's parameter range
        float depth = impostor_depth(k, uv);
        if (depth >= 1e29)
            break; // the object is not at this texel: keep the last point
        float tn = (base + depth) / along;
        if (tn <= 0.0)
            break;
        vec2 un = impostor_uv(k, o + tn * d);
        if (any(lessThan(un, vec2(0.0))) || any(greaterThan(un, vec2(1.0))))
            break;
        t = tn;
        uv = un;
    }
    // The point must lie on the surface the texel holds (issue 8): a seed
    // candidate past the object (the slab's far side) that the correction
    // could not move, or whose move left the impostor, was kept as a hit —
    // rays converging past a small floor's edge were counted on it (a third
    // more light on a 0.6-wide floor than on a 1.2-wide one).
    float surface = impostor_depth(k, uv);
    if (surface >= 1e29)
        return -1.0;
    if (iterations == 0)
        return t; // Fig. 18c: the uncorrected rectangle point, as the paper has it
    float z = dot(o + t * d - im.center.xyz, im.axis.xyz);
    float texel = 2.0 * half_side / float(textureSize(u_impostor_depth, 0).x);
    return abs(z - surface) <= max(0.05 * half_side, 4.0 * texel) ? t : -1.0;
}

// impostor_hit made robust for objects whose impostor is far from a smooth
// height field (several bodies at different depths, deep concavities: the
// dolphins of Fig. 28): the ray is first marched through the impostor's
// slab in `steps` even steps, each point compared with the depth stored at
// its texel, and the first step that passes behind a stored surface is
// bisected; a crossing that does not close onto that surface (the ray
// passing behind a nearer body's edge) is skipped and the march goes on.
// Fig. 16's iteration alone (impostor_hit) lost most photons on the
// dolphins: they went on to the floor, leaving the dolphins dark and
// striped (issue 8). Rays at more than 37 degrees to the impostor's axis
// (a wall's, for light from above: the slab is long along them and the
// steps coarse) or heading back towards its centre side fall back to
// impostor_hit.
float impostor_march(int k, vec3 o, vec3 d, int steps, int iterations, out vec2 uv)
{
    Impostor im = impostors[k];
    float along = dot(d, im.axis.xyz);
    uv = vec2(0.0);
    if (along < 0.8 || steps <= 0)
        return impostor_hit(k, o, d, iterations, uv);
    float base = dot(im.center.xyz - o, im.axis.xyz);
    float half_side = im.center.w;
    float t0 = max((base - half_side) / along, 0.0), t1 = (base + half_side) / along;
    if (t1 <= t0)
        return -1.0;
    float texel = 2.0 * half_side / float(textureSize(u_impostor_depth, 0).x);
    float tolerance = max(0.05 * half_side, 4.0 * texel);
    float prev = t0;
    for (int i = 1; i <= steps; i++) {
        float t = mix(t0, t1, float(i) / float(steps));
        vec3 p = o + t * d;
        float surface = impostor_depth_inside(k, impostor_uv(k, p));
        float z = dot(p - im.center.xyz, im.axis.xyz);
        if (surface < 1e29 && z >= surface) {
            // bisect between the last point in front and this one
            float a = prev, b = t;
            for (int j = 0; j < 8; j++) {
                float m = 0.5 * (a + b);
                vec3 q = o + m * d;
                float sm = impostor_depth_inside(k, impostor_uv(k, q));
                if (sm < 1e29 && dot(q - im.center.xyz, im.axis.xyz) >= sm)
                    b = m;
                else
                    a = m;
            }
            vec3 h = o + b * d;
            vec2 huv = impostor_uv(k, h);
            float sh = impostor_depth(k, huv);
            if (sh < 1e29 && abs(dot(h - im.center.xyz, im.axis.xyz) - sh) <= tolerance) {
                // then Fig. 16's iteration from there (exact on a flat
                // receiver, where the bisection stops within a texel)
                for (int j = 0; j < iterations; j++) {
                    float depth = impostor_depth(k, huv);
                    if (depth >= 1e29)
                        break;
                    float tn = (base + depth) / along;
                    vec2 un = impostor_uv(k, o + tn * d);
                    if (tn <= 0.0 || impostor_depth_inside(k, un) >= 1e29)
                        break;
                    b = tn;
                    huv = un;
                }
                uv = huv;
                return b;
            }
        }
        prev = t;
    }
    return -1.0;
}

// The nearest impostor along a ray: its colour, or false for none.
bool impostor_lookup(vec3 o, vec3 d, int iterations, out vec3 color)
{
    float best = 1e30;
    color = vec3(0.0);
    for (int k = 0; k < u_impostor_count; k++) {
        if (k == u_skip_impostor)
            continue;
        vec2 uv;
        float t = impostor_hit(k, o, d, iterations, uv);
        if (t > 0.0 && t < best) {
            best = t;
            color = texture(u_impostor_color, vec3(uv, float(k))).rgb;
        }
    }
    return best < 1e29;
}
