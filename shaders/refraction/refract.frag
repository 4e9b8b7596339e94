#version 450 core
#include "common/bindings.glsl"
// Hu & Qin §2.1 (or Wyman 2005 with WYMAN): refraction of the environment
// through two interfaces, per fragment of the visible front surface.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#ifdef NEARBY
#ifdef DISTANCE_MAP
#include "distance_map/lookup.glsl"
#ifdef SCREEN_LOOKUP
#include "layers/scene_trace.glsl"
layout(binding = LAYERED_UNIT_SCENE) uniform sampler2D u_scene;
layout(binding = REFRACTION_UNIT_BEHIND) uniform sampler2D u_behind;
layout(binding = REFRACTION_UNIT_INPUT_DEPTH) uniform sampler2D u_input_depth;
#endif
#else
#include "impostors/impostors.glsl"
uniform int u_correction;
#endif
#endif
in vec3 v_world;
in vec3 v_normal;
in float v_thickness;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_tir;  // r: total internal reflections at the two interfaces
layout(location = 2) out vec4 o_exit; // rgb: the direction the path leaves in, a = 1
layout(binding = REFRACTION_UNIT_FRONT_NORMAL) uniform sampler2D u_front_normal;
layout(binding = REFRACTION_UNIT_BACK_NORMAL) uniform sampler2D u_back_normal;
layout(binding = REFRACTION_UNIT_FRONT_DEPTH) uniform sampler2D u_front_depth;
layout(binding = REFRACTION_UNIT_BACK_DEPTH) uniform sampler2D u_back_depth;
uniform float u_ior;
uniform float u_ideal;
uniform vec3 u_absorption;
uniform int u_material_kind; // 2: a mirror
uniform vec3 u_color;
uniform int u_iterations;
uniform float u_tolerance;
uniform int u_search_steps;
uniform int u_reflection; // 0: refraction alone (Fig. 24 a-e)

// What a ray from o in direction d sees: a nearby object in the distance
// map, or its impostor (§2.2, corrected by Fig. 16), or else the environment.
vec3 trace_out(vec3 o, vec3 d)
{
#ifdef NEARBY
    vec3 c;
#ifdef DISTANCE_MAP
    // What the camera sees where the ray goes (searched in the pass's own
    // depth of the diffuse objects): the input image there, unless the input
    // shows the glass itself (shade { specular = true } drew it: its depth
    // there is the refractors' front depth), then the pass's own drawing.
#ifdef SCREEN_LOOKUP
    ivec2 px;
    if (scene_trace(o, d, px)) {
        float glass = texelFetch(u_front_depth, px, 0).r, seen = texelFetch(u_input_depth, px, 0).r;
        bool input_shows_glass = glass < 1.0 && abs(view_depth(seen) - view_depth(glass)) <= 1e-3 * view_depth(glass) + 1e-4;
        return input_shows_glass ? texelFetch(u_behind, px, 0).rgb : texelFetch(u_scene, px, 0).rgb;
    }
#endif
    if (distance_map_lookup(o, d, c))
        return c;
#else
    if (impostor_lookup(o, d, u_correction, c))
        return c;
#endif
#endif
    return environment_radiance(d);
}

// world point -> (uv in [0,1], window depth in [0,1])
vec3 project(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return c.xyz / max(c.w, 1e-6) * 0.5 + 0.5;
}

// window depth at uv -> eye-space distance along -z (positive), for a
// perspective or an orthographic camera
float linear_depth(float d) { return view_depth(d); }

float eye_depth(vec3 p) { return -(u_view * vec4(p, 1.0)).z; }

// A point on the refractor's silhouette-bounded image: is uv inside it?
bool inside(vec2 uv, sampler2D depth_buffer)
{
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) &&
           texture(depth_buffer, uv).r < 1.0;
}

// world position of the surface stored at uv in a depth buffer
vec3 unproject(vec2 uv, float d)
{
    vec4 w = u_inv_view_proj * vec4(vec3(uv, d) * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

#ifndef WYMAN
// §2.1.3, Fig. 9: d_T from a small start, corrected by the depth buffer of
// the surface the ray leaves through, in eye-space depth units.
// `converged`: the ray point ends within 2% of d_T of that surface, on the
// refractor.
float exit_distance(vec3 p1, vec3 t1, bool back, out bool converged)
{
    float dT = 1e-3 * length(p1 - u_camera_pos.xyz);
    vec3 fwd = -vec3(u_view[0][2], u_view[1][2], u_view[2][2]);
    float rate = max(abs(dot(t1, fwd)), 0.05); // eye depth per unit length along T1
    if (back) {
        // start from the thickness along the view ray at P1 (Wyman's d_V):
        // near the answer wherever T1 bends little, and never worse than
        // the paper's small start by more than the iteration corrects
        vec2 uv1 = project(p1).xy;
        float db = texture(u_back_depth, uv1).r;
        if (db < 1.0)
            dT = max(dT, (linear_depth(db) - eye_depth(p1)) / rate);
    }
    converged = false;
    float prev_dT = dT, prev_step = 0.0;
    for (int i = 0; i <= u_iterations; i++) { // capped by the parameter's range; the last pass only measures
        vec3 p2 = p1 + dT * t1;
        vec3 q = project(p2);
        if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))))
            return dT;
        float d = back ? texture(u_back_depth, q.xy).r : texture(u_front_depth, q.xy).r;
        if (d >= 1.0)
            return dT; // off the refractor: keep the last estimate
        // Fig. 9: Steplength = Flag * (depth - z), Flag = -1 for the front-facing surface
        float zbuf = linear_depth(d), zp = eye_depth(p2);
        float step = (back ? zbuf - zp : zp - zbuf) / rate;
        converged = abs(step) < max(0.02 * dT, u_tolerance);
        if (i == u_iterations)
            return dT;
        // Fig. 9's step moves d_T by the depth gap; after the first, a secant
        // through the last two gaps (the gap is smooth along the ray on a
        // smooth surface): three iterations then land where Fig. 9's
        // plain steps need eight (the issue's ball lens edges, README)
        float next = dT + step;
        if (i > 0 && abs(step - prev_step) > 1e-6 * abs(step) + 1e-12) {
            float secant = dT - step * (dT - prev_dT) / (prev_step - step) * -1.0;
            if (secant > 0.0 && abs(secant - dT) < 4.0 * abs(step) + 1e-6)
                next = secant;
        }
        prev_dT = dT;
        prev_step = step;
        dT = max(next, 0.0);
        if (abs(step) < u_tolerance)
            return dT;
    }
    return dT;
}
#endif

void main()
{
    vec3 n1 = normalize(v_normal);
    vec3 v = view_direction(v_world);
    if (dot(v, n1) > 0.0)
        n1 = -n1;
    o_tir = vec4(0.0);
    o_exit = vec4(reflect(v, n1), 1.0);
    if (u_material_kind == 2) { // a mirror: reflection alone, of nearby objects too
        o_color = vec4(u_color * trace_out(v_world, reflect(v, n1)), 1.0);
        return;
    }
    float eta = 1.0 / u_ior;
    float f1 = fresnel_of(-dot(v, n1), eta, u_ideal);
    vec3 reflected = trace_out(v_world, reflect(v, n1));
    vec3 t1 = refract(v, n1, eta);
    if (dot(t1, t1) == 0.0) { // total internal reflection at the entry (an IOR below 1)
        o_tir = vec4(1.0, 0.0, 0.0, 1.0);
        o_color = vec4(reflected, 1.0);
        return;
    }
    t1 = normalize(t1);
    vec3 p1 = v_world;
    vec2 uv1 = project(p1).xy;

    bool back = true;
    float dT;
#ifdef WYMAN
    // Wyman 2005: d_T ~ (theta_t / theta_i) d_V + (1 - theta_t / theta_i) d_N, with
    // d_V the view ray's thickness from the two depth buffers and d_N precomputed.
    float ti = acos(clamp(-dot(v, n1), -1.0, 1.0)), tt = acos(clamp(-dot(t1, n1), -1.0, 1.0));
    float ratio = ti > 1e-4 ? clamp(tt / ti, 0.0, 1.0) : 1.0;
    float dV = max(linear_depth(texture(u_back_depth, uv1).r) - eye_depth(p1), 0.0) / max(dot(v, -vec3(u_view[0][2], u_view[1][2], u_view[2][2])), 1e-3);
    dT = ratio * dV + (1.0 - ratio) * v_thickness;
#else
    // §2.1.2 decides between the back- and the front-facing surface by the
    // dividing pixel p_e (a binary search along the projected T1, Fig. 7)
    // and the angles to it. That test flips at random across the outer
    // part of a sphere (p_e's pixel quantization moves P_e's depth a lot
    // where the back surface turns away: concentric rings of wrong exits,
    // the issue's "dotted rim"). Instead both are tried with Fig. 9's
    // iteration: a front-facing exit is taken when its iteration converges
    // onto the front surface ahead of the back one (a concave part the ray
    // leaves through towards the camera); otherwise the back-facing one.
    bool front_converged;
    float dT_front = exit_distance(p1, t1, false, front_converged);
    bool back_converged;
    dT = exit_distance(p1, t1, true, back_converged);
    back = !(front_converged && dT_front > 1e-2 * dT && (dT_front < dT || !back_converged));
    if (!back)
        dT = dT_front;
#endif
    vec3 p2 = p1 + dT * t1;
    vec2 uv2 = project(p2).xy;
    vec3 n2 = back ? texture(u_back_normal, uv2).xyz : texture(u_front_normal, uv2).xyz;
    if (dot(n2, n2) < 0.5)
        n2 = back ? texture(u_back_normal, uv1).xyz : -n1; // outside the buffer: the nearest guess
    n2 = normalize(n2);
    // leaving: the normal facing against the ray is -n2 (n2 is outward)
    vec3 m = dot(t1, n2) > 0.0 ? -n2 : n2;
    float f2 = fresnel_of(-dot(t1, m), u_ior, u_ideal);
    vec3 t2 = refract(t1, m, u_ior);
    vec3 exit_dir = dot(t2, t2) > 0.0 ? normalize(t2) : reflect(t1, m); // TIR: the reflected ray (approximation)
    o_tir = vec4(dot(t2, t2) > 0.0 ? 0.0 : 1.0, 0.0, 0.0, 1.0);
    o_exit = vec4(exit_dir, 1.0);
    vec3 transmitted = trace_out(p2, exit_dir) * exp(-u_absorption * dT);
    if (dot(t2, t2) > 0.0)
        transmitted *= (1.0 - f2);
    o_color = vec4(u_reflection == 1 ? f1 * reflected + (1.0 - f1) * transmitted : transmitted, 1.0);
}
