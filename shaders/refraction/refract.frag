#version 450 core
// Hu & Qin §2.1 (or Wyman 2005 with WYMAN): refraction of the environment
// through two interfaces, per fragment of the visible front surface.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "common/surface_normal.glsl"
#include "common/lighting.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"
#include "common/roles.glsl"
#ifdef NEARBY
#ifdef DISTANCE_MAP
#include "distance_map/lookup.glsl"
#ifdef SCREEN_LOOKUP
#include "layers/scene_trace.glsl"
uniform sampler2D u_scene;
uniform sampler2D u_behind;
uniform sampler2D u_scene_mips;  // u_scene and u_behind with mipmaps, for rough glass (refraction.c)
uniform sampler2D u_behind_mips;
uniform sampler2D u_input_depth;
#endif
#else
#include "impostors/impostors.glsl"
#endif
#endif
// The pass's parameters, one block uploaded in one call each frame: its C
// mirror is refraction.c's struct refraction_params, whose layout is
// checked against this one when the program is linked (std140: each member
// 4 bytes, in this order).
layout(std140) uniform RefractionParams {
    int u_iterations;   // of the d_T lookup (Fig. 9)
    float u_tolerance;  // its stopping step
    int u_search_steps; // for the dividing pixel p_e (Fig. 7)
    int u_correction;   // of the impostor lookup (Fig. 16)
    int u_reflection;   // 0: refraction alone (Fig. 24 a-e)
    float u_reach;      // the refractors' bounding diameter (marches inside them)
    int u_internal;     // interfaces a path meets from the first exit on (1: the paper's two)
};
in vec3 v_world;
in vec3 v_normal;
in float v_thickness;
uniform int u_camera_inside = 0; // 1: the camera is inside this refractor (its back faces are drawn)
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_tir;  // r: total internal reflection at the two interfaces, g: all of them
layout(location = 2) out vec4 o_exit; // rgb: the direction the path leaves in, a = 1
uniform sampler2D u_front_normal;
uniform sampler2D u_back_normal;
uniform sampler2D u_front_depth;
uniform sampler2D u_back_depth;
uniform float u_ior;
uniform float u_roughness; // GGX roughness of rough glass (glTF's: alpha = roughness^2); 0: smooth
uniform float u_transmission = 1.0; // the glass's share of the surface; the rest is diffuse of u_color
uniform vec3 u_tint = vec3(1.0);    // the light through it, once (glTF's base colour as its transmission tint)
uniform sampler2D u_transmission_texture; // x its red channel per texel (glTF's transmissionTexture)
uniform int u_transmission_set;           // 0: none, 1: TEXCOORD_0, 2: TEXCOORD_1
uniform vec3 u_transmission_transform[2]; // uv' = (dot(row0, (uv, 1)), dot(row1, (uv, 1)))
in vec2 v_texcoord0;
in vec2 v_texcoord1;
// glTF's baseColorTexture on glass: x the tint per texel where the light
// enters (bound by renderer_draw_objects in common/material.glsl's slot 0)
uniform sampler2D u_base_color_texture;
uniform int u_texture_set[5];
uniform vec3 u_texture_transform[10];
#include "refraction/interface_normal.glsl"
// glTF's alphaMode on glass and mirrors: material_alpha, material_cut_out
#include "common/alpha.glsl"

// The tint of the light entering here: the base colour x its texture (the
// reference's ref_glass_tint)
vec3 glass_tint()
{
    if (u_texture_set[0] == 0)
        return u_tint;
    vec3 q = vec3(u_texture_set[0] == 2 ? v_texcoord1 : v_texcoord0, 1.0);
    return u_tint * texture(u_base_color_texture, vec2(dot(u_texture_transform[0], q), dot(u_texture_transform[1], q))).rgb;
}
uniform float u_ideal;
uniform vec3 u_absorption;
uniform vec3 u_color;

// What a ray from o in direction d sees: a nearby object in the distance
// map, or its impostor (§2.2, corrected by Fig. 16); false: the
// environment (looked up at the end of main, filtered over the pixel).
// `weight`: how much of the pixel this ray carries; a ray under a tenth
// (a Fresnel reflection, the part reflected inside) is looked up in the
// distance map alone with a third of the steps (on llvmpipe the searches
// are most of the pass's time).
#ifdef SCREEN_LOOKUP
// What the camera sees at pixel px: the input image, unless the input
// shows the glass itself (shade { specular = true } drew it: its depth
// there is the refractors' front depth), then the pass's own drawing.
vec3 seen_at(ivec2 px)
{
    px = clamp(px, ivec2(0), ivec2(u_viewport.xy) - 1);
    float glass = texelFetch(u_front_depth, px, 0).r, seen = texelFetch(u_input_depth, px, 0).r;
    if (u_camera_inside == 1 && glass >= 1.0) // the camera inside: the glass it sees is its back faces
        glass = texelFetch(u_back_depth, px, 0).r;
    bool input_shows_glass = glass < 1.0 && abs(view_depth(seen) - view_depth(glass)) <= 1e-3 * view_depth(glass) + 1e-4;
    return input_shows_glass ? texelFetch(u_behind, px, 0).rgb : texelFetch(u_scene, px, 0).rgb;
}

// Rough glass seen through (a cone lookup): the refracted ray's direction
// spreads by the microfacet normals' tilt at the two interfaces. A facet
// tilted by theta turns a ray entering glass of index n by about
// theta (1 - 1/n) and one leaving by theta (n - 1), so the ray that leaves
// spreads by about alpha (n - 1/n), alpha = roughness^2 being GGX's median
// tan theta (Walter et al. 2007, eq. 33). Over the distance to what the
// ray meets that is a disc of radius t tan(spread): read from the input's
// mipmaps at the level whose texels are that disc's radius, as a centre
// and a ring of six taps (Gaussian-like weights). The input or the pass's
// own drawing behind the glass is chosen by the centre pixel, as
// seen_at does. The reference samples the facets themselves
// (ref_microfacet.c); this is the GPU's stand-in (docs/GLTF.md).
vec3 seen_rough(ivec2 px, vec3 hit)
{
    float alpha = u_roughness * u_roughness;
    // (a rough mirror: a facet tilted by theta turns the reflected ray by 2 theta)
    float spread = role_is(ROLE_MIRROR) ? 2.0 * alpha : alpha * abs(u_ior - 1.0 / u_ior);
    float z = u_proj[3][3] == 0.0 ? max(-(u_view * vec4(hit, 1.0)).z, 1e-6) : 1.0;
    float pixel = 2.0 * z / (u_proj[1][1] * u_viewport.y); // a pixel's size at the hit
    float radius = length(hit - v_world) * tan(min(spread, 1.2)) / max(pixel, 1e-9);
    if (radius < 0.5)
        return seen_at(px);
    px = clamp(px, ivec2(0), ivec2(u_viewport.xy) - 1);
    float glass = texelFetch(u_front_depth, px, 0).r, seen = texelFetch(u_input_depth, px, 0).r;
    bool behind = glass < 1.0 && abs(view_depth(seen) - view_depth(glass)) <= 1e-3 * view_depth(glass) + 1e-4;
    vec2 uv = (vec2(px) + 0.5) * u_viewport.zw;
    float lod = log2(radius);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int k = 0; k < 7; k++) {
        float a = float(k) * 1.0471976, w = k == 0 ? 2.0 : 1.0;
        vec2 at = uv + (k == 0 ? vec2(0.0) : vec2(cos(a), sin(a)) * radius * u_viewport.zw);
        sum += w * (behind ? textureLod(u_behind_mips, at, lod).rgb : textureLod(u_scene_mips, at, lod).rgb);
        weights += w;
    }
    return sum / weights;
}
#endif

bool trace_nearby(vec3 o, vec3 d, float weight, out vec3 c)
{
    c = vec3(0.0);
#ifdef NEARBY
#ifdef DISTANCE_MAP
    // What the camera sees where the ray goes (searched in the pass's own
    // depth of the diffuse objects): the input image there, unless the input
    // shows the glass itself (shade { specular = true } drew it: its depth
    // there is the refractors' front depth), then the pass's own drawing.
#ifdef SCREEN_LOOKUP
    ivec2 px;
    float t_hit;
    if (weight >= 0.1 && scene_trace_at(o, d, px, t_hit)) {
        c = u_roughness > 0.0 ? seen_rough(px, o + d * t_hit) : seen_at(px);
        return true;
    }
#endif
    if (distance_map_lookup(o, d, weight >= 0.1 ? u_distance_steps : max(u_distance_steps / 3, 4), c))
        return true;
#else
    if (impostor_lookup(o, d, u_correction, c))
        return true;
#endif
#endif
    return false;
}

// The pixel's radiance: the nearby objects' found at once; the reflected
// ray and the first ray leaving the refractor that see the environment are
// kept here and looked up at the end of main, where the screen derivatives
// of their directions are defined (uniform control flow); fainter ones
// (the parts reflected inside) at once, unfiltered.
vec3 pixel_radiance = vec3(0.0);
vec3 reflected_env_dir = vec3(0.0), reflected_env_weight = vec3(0.0);
vec3 exit_env_dir = vec3(0.0), exit_env_weight = vec3(0.0);
bool exit_env_taken = false;

// Adds what the ray from o along d sees, times w, to the pixel
// (`importance`: trace_nearby's weight).
void gather(vec3 o, vec3 d, vec3 w, float importance, bool reflected)
{
    vec3 c;
    if (trace_nearby(o, d, importance, c))
        pixel_radiance += w * c;
    else if (reflected) {
        reflected_env_dir = d;
        reflected_env_weight = w;
    } else if (!exit_env_taken) {
        exit_env_dir = d;
        exit_env_weight = w;
        exit_env_taken = true;
    } else
        pixel_radiance += w * environment_radiance(d);
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
float exit_distance(vec3 p1, vec3 t1, bool back, int iterations, out bool converged)
{
    float dT = 1e-3 * length(p1 - u_camera_pos.xyz);
    vec3 fwd = -vec3(u_view[0][2], u_view[1][2], u_view[2][2]);
    // eye depth per unit length along T1, signed (a reflected ray inside
    // may head back towards the camera), at least 0.05 in size
    float along = dot(t1, fwd);
    float rate = along < 0.0 ? min(along, -0.05) : max(along, 0.05);
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
    for (int i = 0; i <= iterations; i++) { // capped by the callers (16 at most); the last pass only measures
        vec3 p2 = p1 + dT * t1;
        vec3 q = project(p2);
        if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))))
            return dT;
        float d = back ? texture(u_back_depth, q.xy).r : texture(u_front_depth, q.xy).r;
        if (d >= 1.0)
            return dT; // off the refractor: keep the last estimate
        // Fig. 9: Steplength = Flag * (depth - z), Flag = -1 for the
        // front-facing surface: for T1 heading away from the camera. Here
        // the step is the depth gap over the signed depth rate, which is
        // that for T1 and also serves a ray heading back (after a total
        // internal reflection), for either surface.
        float zbuf = linear_depth(d), zp = eye_depth(p2);
        float step = (zbuf - zp) / rate;
        converged = abs(step) < max(0.02 * dT, u_tolerance);
        if (i == iterations)
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

// After a total internal reflection the ray may head anywhere inside, so
// instead of Fig. 9's iteration (which assumes T1 heads away from the
// camera) the next interface is found by marching between the front and
// back depths (the photons' march in the light's view is the same).
#include "common/depth_march.glsl"
#endif

// The paths through the refractor from the surface point v_world (view
// direction v, normal n1 facing the camera), gathered into the pixel;
// exit_dir: the direction the light first leaves along; exit_key: the
// normal of the first interface inside and the number of total internal
// reflections (where either jumps between neighbouring pixels the path
// changed there: a cube's edge seen through its front face).
void leave_glass(vec3 pos, vec3 dir, vec3 n2, vec3 throughput, float transmitted_share, inout vec3 exit_dir,
                 inout vec4 exit_key);

void refract_paths(vec3 v, vec3 n1, vec3 reflect_dir, inout vec3 exit_dir, inout vec4 exit_key)
{
    float eta = 1.0 / u_ior;
    float f1 = fresnel_of(-dot(v, n1), eta, u_ideal);
    vec3 t1 = refract(v, n1, eta);
    bool entry_tir = dot(t1, t1) == 0.0;
    if (entry_tir) { // total internal reflection at the entry (an IOR below 1)
        o_tir = vec4(1.0, 1.0, 0.0, 1.0);
        gather(v_world, reflect_dir, vec3(1.0), 1.0, true);
        return;
    }
    if (u_reflection == 1)
        gather(v_world, reflect_dir, vec3(f1), f1, true);
    float transmitted_share = u_reflection == 1 ? 1.0 - f1 : 1.0;
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
    float dT_front = exit_distance(p1, t1, false, u_iterations, front_converged);
    bool back_converged;
    dT = exit_distance(p1, t1, true, u_iterations, back_converged);
    back = !(front_converged && dT_front > 1e-2 * dT && (dT_front < dT || !back_converged));
    if (!back)
        dT = dT_front;
#endif
    vec3 p2 = p1 + dT * t1;
    vec2 uv2 = project(p2).xy;
    vec3 n2 = back ? surface_normal(u_back_normal, uv2) : surface_normal(u_front_normal, uv2);
    if (dot(n2, n2) < 0.5)
        n2 = back ? surface_normal(u_back_normal, uv1) : -n1; // outside the buffer: the nearest guess
    n2 = normalize(n2);
    exit_dir = reflect(t1, dot(t1, n2) > 0.0 ? -n2 : n2);
    leave_glass(p2, t1, n2, transmitted_share * glass_tint() * exp(-u_absorption * dT), transmitted_share, exit_dir, exit_key);
}

// From inside the glass at its surface `pos` (outward normal n2), going
// along dir with `throughput` left of the pixel's `transmitted_share`: out
// through the interface, or on inside after a total internal reflection.
void leave_glass(vec3 pos, vec3 dir, vec3 n2, vec3 throughput, float transmitted_share, inout vec3 exit_dir,
                 inout vec4 exit_key)
{
    exit_key.xyz = n2;
    // Leaving: the normal facing against the ray is -n2 (n2 is outward).
    // Beyond the paper's two interfaces (issue 8): at a total internal
    // reflection the ray reflects and the next interface is found by
    // depth_march; where it can leave, the Fresnel-reflected part goes on
    // inside the same way (a diamond's internal reflections: 17% at normal
    // incidence for n = 2.42), until MAX_INTERFACES interfaces or until
    // what remains is under 3%. Whatever is still inside then leaves along
    // its last direction. Wyman's method keeps two interfaces.
#ifdef WYMAN
    const int MAX_INTERFACES = 1;
#else
    int MAX_INTERFACES = clamp(u_internal, 1, 8);
#endif
    int tir = 0, tir_first = 0;
    bool left = false;
    for (int crossing = 0; crossing < MAX_INTERFACES; crossing++) {
        vec3 m = dot(dir, n2) > 0.0 ? -n2 : n2;
        vec3 t2 = refract(dir, m, u_ior);
        if (dot(t2, t2) > 0.0) {
            float f2 = fresnel_of(-dot(dir, m), u_ior, u_ideal);
            if (!left)
                exit_dir = normalize(t2); // the first way out (the `exit` output)
            left = true;
            vec3 w = throughput * (1.0 - f2);
            gather(pos, normalize(t2), w, max(w.r, max(w.g, w.b)) / transmitted_share, false);
            throughput *= f2;
        } else {
            tir++;
            if (crossing == 0)
                tir_first = 1;
        }
        dir = reflect(dir, m);
        if (max(throughput.r, max(throughput.g, throughput.b)) < 0.03 * transmitted_share || crossing + 1 == MAX_INTERFACES)
            break;
#ifndef WYMAN
        // start a little inside, off the surface it reflected off
        vec3 start = pos + dir * (1e-3 * u_reach);
        float d, d_inside;
        bool use_back;
        if (!depth_march(start, dir, u_reach, d, d_inside, use_back))
            break; // still inside after the whole reach: leaves along the reflection below
        vec2 q = project(start + d_inside * dir).xy;
        vec3 nn = use_back ? surface_normal(u_back_normal, q) : surface_normal(u_front_normal, q);
        if (dot(nn, nn) < 0.5)
            break;
        pos = start + d * dir;
        throughput *= exp(-u_absorption * d);
        n2 = normalize(nn);
#endif
    }
    if (max(throughput.r, max(throughput.g, throughput.b)) >= 0.03 * transmitted_share)
        gather(pos, dir, throughput, max(throughput.r, max(throughput.g, throughput.b)) / transmitted_share, false); // still inside
    if (!left)
        exit_dir = dir;
    exit_key.w = float(tir);
    o_tir = vec4(float(tir_first), float(tir), 0.0, 1.0);
}

void main()
{
    // through the normal map where the surface has one (interface_normal.glsl,
    // as the reference maps it), in uniform control flow (its derivatives)
    vec3 mapped = interface_normal(normalize(v_normal));
    vec3 n1 = mapped;
    vec3 v = view_direction(v_world);
    if (dot(v, n1) > 0.0)
        n1 = -n1;
    vec3 reflect_dir = reflect(v, n1);
    o_tir = vec4(0.0);
    vec3 exit_dir = reflect_dir; // the first way out (the `exit` output)
    vec4 exit_key = vec4(n1, 0.0);
    // the far side of glass or a mirror with holes, seen through a hole in
    // its front (refraction.c draws such objects' back faces too)
    bool far_side = !gl_FrontFacing && u_camera_inside == 0;
    if (role_is(ROLE_MIRROR)) // a mirror: reflection alone, of nearby objects too
        gather(v_world, reflect_dir, u_color, 1.0, true);
    else if (u_camera_inside == 1 || far_side) {
        // The camera inside the glass (Hu & Qin's two interfaces assume it
        // outside): the view ray is in the glass already, absorbed on the way
        // to this back face, and meets only the way out. Where a front face
        // lies nearer (an orthographic camera's rays that start outside),
        // the front-face drawing stands.
        if (texelFetch(u_front_depth, ivec2(gl_FragCoord.xy), 0).r < gl_FragCoord.z)
            discard;
        vec3 n_out = mapped;
        if (dot(v, n_out) < 0.0)
            n_out = -n_out;
        reflect_dir = v; // no reflection off the outside to filter
        exit_dir = v;
        // (a ray in through a hole crossed no surface: unabsorbed, as the
        // reference's media stack has it)
        leave_glass(v_world, v, n_out, far_side ? vec3(1.0) : exp(-u_absorption * view_distance(v_world)), 1.0,
                    exit_dir, exit_key);
    } else
        refract_paths(v, n1, reflect_dir, exit_dir, exit_key);
    // The environment over each pixel's spread of directions (issue 8): the
    // exit direction's screen derivatives for the rays leaving the
    // refractor, the reflection's for the reflected one. Derivatives are
    // differences between neighbouring pixels: where the path changes
    // between them (another face inside, another count of total internal
    // reflections), the difference is not a pixel's spread, and that axis
    // is not filtered (the reflection's spread is only clamped).
    vec4 kx = dFdx(exit_key), ky = dFdy(exit_key);
    const float JUMP = 0.5; // radians of normal between neighbouring pixels
    vec3 ex = dFdx(exit_dir), ey = dFdy(exit_dir), rx = dFdx(reflect_dir), ry = dFdy(reflect_dir);
    ex *= float(length(kx.xyz) < JUMP && kx.w == 0.0);
    ey *= float(length(ky.xyz) < JUMP && ky.w == 0.0);
    if (reflected_env_weight != vec3(0.0))
        pixel_radiance += reflected_env_weight * environment_radiance_grad(reflected_env_dir, rx, ry);
    if (exit_env_taken)
        pixel_radiance += exit_env_weight * environment_radiance_grad(exit_env_dir, ex, ey);
    o_exit = vec4(exit_dir, 1.0);
    // Partial transmission (glTF's transmissionFactor t < 1): the surface is
    // t glass and 1 - t diffuse of u_color, the weights the reference picks
    // a path's by. The diffuse share is lit by the lights, through the
    // shadow maps given as `shadow` (unshadowed without them), and by the
    // ambient sky.
    float transmission = u_transmission;
    if (u_transmission_set > 0) {
        vec3 q = vec3(u_transmission_set == 2 ? v_texcoord1 : v_texcoord0, 1.0);
        transmission *= texture(u_transmission_texture,
                                vec2(dot(u_transmission_transform[0], q), dot(u_transmission_transform[1], q))).r;
    }
    if (transmission < 1.0 && !role_is(ROLE_MIRROR)) {
        vec3 diffuse = surface_light_diffuse(v_world, n1, u_color, vec3(0.0), vec3(0.0));
        pixel_radiance = transmission * pixel_radiance + (1.0 - transmission) * diffuse;
    }
    // glTF's alphaMode on glass and mirrors (issue 50), after the
    // derivatives: MASK cuts a hole, through which the input image shows
    // undeviated; BLEND covers alpha of the pixel, blended over the input
    // (refraction.c blends such objects' colour). The reference keeps the
    // same surfaces (ref_scene.c's filter).
    if (u_alpha_blend == 0 && material_cut_out())
        discard;
    // a mirror's inner side, drawn where it has holes (refraction.c), is
    // seen only where no front face lies nearer (the front surfaces' depth
    // keeps the holes out; glass's far side was tested above)
    if (far_side && texelFetch(u_front_depth, ivec2(gl_FragCoord.xy), 0).r < gl_FragCoord.z)
        discard;
    o_color = vec4(pixel_radiance, u_alpha_blend == 1 ? clamp(material_alpha(), 0.0, 1.0) : 1.0);
}
