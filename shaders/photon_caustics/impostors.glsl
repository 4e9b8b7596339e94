// The impostors' frames (src/passes/impostors.h) and the ray lookup of Hu &
// Qin §2.2: intersect a ray with the rectangles, then correct the hit with
// the depth texture (the iterative lookup of Fig. 16).
struct Impostor {
    vec4 center; // xyz, w = half side d_i
    vec4 axis;
    vec4 right;
    vec4 up;
};
layout(std430, binding = 5) readonly buffer Impostors { Impostor impostors[]; };
layout(binding = 6) uniform sampler2DArray u_impostor_depth;
layout(binding = 8) uniform sampler2DArray u_impostor_color;
uniform int u_impostor_count;

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

// Where does the ray (o, d) meet the object of impostor k? Starts at the
// rectangle (P_rect), then `iterations` times: look up the depth at the
// current point's texel and move along the ray to that depth. Returns the
// distance t (or -1 for a miss) and the texel uv.
float impostor_hit(int k, vec3 o, vec3 d, int iterations, out vec2 uv)
{
    Impostor im = impostors[k];
    float along = dot(d, im.axis.xyz);
    if (abs(along) < 1e-4)
        return -1.0; // the rectangle seen edge-on: no hit (never a division by ~0)
    float base = dot(im.center.xyz - o, im.axis.xyz);
    float t = base / along;
    if (t <= 0.0)
        return -1.0;
    uv = impostor_uv(k, o + t * d);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return -1.0;
    for (int i = 0; i < iterations; i++) { // capped by the caller's parameter range
        float depth = impostor_depth(k, uv);
        if (depth >= 1e29)
            break; // the object is not at this texel: keep the rectangle's point
        float tn = (base + depth) / along;
        if (tn <= 0.0)
            break;
        vec2 un = impostor_uv(k, o + tn * d);
        if (any(lessThan(un, vec2(0.0))) || any(greaterThan(un, vec2(1.0))))
            break;
        t = tn;
        uv = un;
    }
    return impostor_depth(k, uv) < 1e29 ? t : -1.0;
}

// The nearest impostor along a ray: its colour, or false for none.
bool impostor_lookup(vec3 o, vec3 d, int iterations, out vec3 color)
{
    float best = 1e30;
    color = vec3(0.0);
    for (int k = 0; k < u_impostor_count; k++) {
        vec2 uv;
        float t = impostor_hit(k, o, d, iterations, uv);
        if (t > 0.0 && t < best) {
            best = t;
            color = texture(u_impostor_color, vec3(uv, float(k))).rgb;
        }
    }
    return best < 1e29;
}
