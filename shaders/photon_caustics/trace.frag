#version 450 core
// Hu & Qin §3.1: one photon per photon-buffer pixel that sees a refractor
// (or mirror) from the light. It enters (Fresnel, Snell), crosses the
// object (d_T by the depth-buffer iteration of Fig. 9, in the light's
// view), leaves (Fresnel, Snell; after a total internal reflection it is
// marched to its next interface, issue 8), and
// meets the nearest receiver impostor (Fig. 16 correction). Out: (u, v, k)
// and its flux: the light's irradiance over the pixel's footprint times
// the two transmittances and Beer-Lambert absorption.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "common/roles.glsl"
#include "common/shadows.glsl"
#include "common/surface_normal.glsl"
#include "impostors/impostors.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_photon;
layout(location = 1) out vec4 o_flux;
uniform sampler2D u_front_normal;
uniform sampler2D u_back_normal;
uniform sampler2D u_front_depth;
uniform sampler2D u_back_depth;
uniform mat4 u_light_view_proj;
uniform mat4 u_light_inverse;
uniform int u_light;
uniform int u_iterations;
uniform float u_buffer;
uniform float u_reach; // the specular objects' bounding diameter: how far a photon inside is marched
uniform int u_reflect_glass; // mode "reflect": follow the light glass reflects (Fresnel-weighted)
uniform sampler2D u_front_material; // rgb absorption (a mirror's tint), w the roles (common/roles.glsl)

vec3 unproject(vec2 uv, float d)
{
    vec4 w = u_light_inverse * vec4(vec3(uv, d) * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

vec3 project(vec3 p)
{
    vec4 c = u_light_view_proj * vec4(p, 1.0);
    return c.xyz / max(c.w, 1e-6) * 0.5 + 0.5;
}

// After a total internal reflection the photon may head anywhere inside:
// its next interface is found by marching in the light's view (as the
// refraction pass does in the camera's).
#include "common/depth_march.glsl"

// From `from` (on an interface) along d inside the objects, the next
// interface by depth_march: the distance to it, where, and its normal
// (the back or front buffer's, by which it crosses; unnormalised, short
// where neither buffer holds a surface there). False: none within u_reach.
bool next_interface(vec3 from, vec3 d, out float t, out vec3 at, out vec3 n)
{
    vec3 start = from + d * (1e-3 * u_reach);
    float t_exit, t_inside;
    bool through_back;
    if (!depth_march(start, d, u_reach, t_exit, t_inside, through_back))
        return false;
    vec2 q = project(start + t_inside * d).xy;
    n = through_back ? surface_normal(u_back_normal, q) : surface_normal(u_front_normal, q);
    t = t_exit + 1e-3 * u_reach;
    at = start + t_exit * d;
    return true;
}

void nothing()
{
    o_photon = vec4(0.0);
    o_flux = vec4(0.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 uv = (vec2(px) + 0.5) / u_buffer;
    float d1 = texelFetch(u_front_depth, px, 0).r;
    if (d1 >= 1.0) {
        nothing();
        return;
    }
    GpuLight light = u_lights[u_light];
    int kind = int(light.position.w + 0.5);
    vec3 p1 = unproject(uv, d1);
    vec3 ldir = kind == 1 ? normalize(light.direction.xyz) : normalize(p1 - light.position.xyz);
    // irradiance perpendicular to the light at p1, and the pixel's footprint across the beam
    vec3 e = light.intensity.rgb;
    if (kind != 1) {
        vec3 d = p1 - light.position.xyz;
        e /= max(dot(d, d), 1e-8);
        if (kind == 2)
            e *= smoothstep(light.direction.w, max(light.intensity.w, light.direction.w + 1e-4),
                            dot(ldir, normalize(light.direction.xyz)));
    }
    vec3 a = unproject(uv + vec2(1.0 / u_buffer, 0.0), d1) - p1, b = unproject(uv + vec2(0.0, 1.0 / u_buffer), d1) - p1;
    vec3 flux = e * abs(dot(cross(a, b), ldir));
    // thin-walled panes between the light and the glass: what they let
    // through, (1 - F) x tint, from the light's shadow map where the pass
    // reads one (its pane filter, shadow_map/thin_filter.frag), as the
    // reference's photons cross them (issue 50)
    flux *= pane_filter(u_light, p1, texelFetch(u_front_normal, px, 0).xyz, -ldir);
    vec4 front = texelFetch(u_front_normal, px, 0);
    vec3 n1 = normalize(front.xyz);
    // the material of the object this photon meets (several may be in view)
    vec4 material = texelFetch(u_front_material, px, 0);
    bool is_mirror = front.w < 0.0;
    float ideal = !is_mirror && front.w >= IDEAL_IOR_OFFSET ? 1.0 : 0.0;
    float ior = is_mirror ? 1.5 : front.w - ideal * IDEAL_IOR_OFFSET;
    vec3 absorption = is_mirror ? vec3(0.0) : material.rgb;
    vec3 tint = is_mirror ? material.rgb : vec3(1.0);
    bool single = (int(material.w + 0.5) & ROLE_WATER) != 0; // water: one interface (Fig. 28)
    if (dot(ldir, n1) > 0.0)
        n1 = -n1;
    float eps = 1e-4 * length(p1 - unproject(vec2(0.5), 0.5)) + 1e-5;
    vec3 origin, dir;
    if (is_mirror || u_reflect_glass == 1) {
        dir = reflect(ldir, n1); // reflective caustics (Fig. 19 bottom)
        origin = p1 + n1 * eps;
        flux *= is_mirror ? tint : vec3(fresnel_of(-dot(ldir, n1), 1.0 / ior, ideal));
    } else {
        float f1 = fresnel_of(-dot(ldir, n1), 1.0 / ior, ideal);
        vec3 t1 = refract(ldir, n1, 1.0 / ior);
        bool outside_tir = dot(t1, t1) == 0.0;
        if (outside_tir) {
            // an IOR below 1 reflects everything at the entry: the photon
            // goes on off the outside, all of it (issue 8: dropping it lost
            // 47% of the light under an IOR 0.8 cube)
            dir = reflect(ldir, n1);
            origin = p1 + n1 * eps;
        } else if (single) {
            t1 = normalize(t1);
            flux *= 1.0 - f1;
            dir = t1;
            origin = p1 - n1 * eps;
        } else {
        t1 = normalize(t1);
        flux *= 1.0 - f1;
        // d_T (Fig. 9): move to the back surface along the light's view.
        // As the refraction pass does (refraction/refract.frag,
        // exit_distance): start from the thickness along the light's ray at
        // p1 (Wyman's d_V) rather than Fig. 9's small start, after the first
        // step take the secant through the last two gaps, and iterate until
        // the gap closes (at most D_T_STEPS), not for `iterations`. Fig. 9's
        // plain step assumes a back surface square to the light; a tilted
        // one, or a crease between two back faces, needs more steps than
        // the paper's few: a tilted IOR 2.42 cube put 0.905 of an exact
        // trace's light on the floor with 3 (its two lit faces' caustics
        // parted by a dim band), 0.947 with 4, 0.956 with 5 to 16.
        vec3 view1 = kind == 1 ? ldir : normalize(p1 - light.position.xyz);
        float rate = max(abs(dot(t1, view1)), 0.05);
        float dT = 1e-3;
        float db1 = texelFetch(u_back_depth, px, 0).r;
        if (db1 < 1.0)
            dT = max(dT, dot(unproject(uv, db1) - p1, view1) / rate);
        float prev_dT = dT, prev_step = 0.0;
        const int D_T_STEPS = 8;
        for (int i = 0; i < D_T_STEPS; i++) {
            vec3 q = project(p1 + dT * t1);
            if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))))
                break;
            float db = texture(u_back_depth, q.xy).r;
            if (db >= 1.0)
                break;
            vec3 pb = unproject(q.xy, db);
            vec3 view = kind == 1 ? ldir : normalize(pb - light.position.xyz);
            float step = dot(pb - (p1 + dT * t1), view) / max(abs(dot(t1, view)), 0.05);
            float next = dT + step;
            if (i > 0 && abs(step - prev_step) > 1e-6 * abs(step) + 1e-12) {
                float secant = dT + step * (dT - prev_dT) / (prev_step - step);
                if (secant > 0.0 && abs(secant - dT) < 4.0 * abs(step) + 1e-6)
                    next = secant;
            }
            prev_dT = dT;
            prev_step = step;
            dT = max(next, 0.0);
            if (abs(step) < 1e-4 * dT + 1e-6)
                break;
        }
        vec3 p2 = p1 + dT * t1;
        vec3 n2 = surface_normal(u_back_normal, project(p2).xy);
        // Fig. 9 finds where the photon meets the back surface, the faces
        // turned away from the light. A photon bent steeply at the entry
        // can leave first through a face turned towards the light (a cube's
        // lit side face, the sun 40 degrees off the zenith: issue 52, case
        // 3, a strip of its caustic missing): where the way to p2 passes in
        // front of the front surface, the photon's exit is marched in both
        // depth buffers (as after a total internal reflection) instead.
        // The front depth is read at the nearest texel; one that holds no
        // surface is outside the objects' outline, so the photon left too
        // (by a face edge-on to the light). The march is not better
        // everywhere: the IOR-0.8 cube, whose light bends outwards at the
        // entry and leaves by its sides, went 0.029 -> 0.038 (and 0.043
        // with only the photons marched out by a front face).
        bool left_by_front = false;
        for (int i = 1; i < 8 && !left_by_front; i++) {
            vec3 q = project(p1 + (float(i) / 8.0) * dT * t1);
            if (all(greaterThanEqual(q.xy, vec2(0.0))) && all(lessThan(q.xy, vec2(1.0)))) {
                float zf = texelFetch(u_front_depth, ivec2(q.xy * u_buffer), 0).r;
                left_by_front = zf >= 1.0 || q.z < zf;
            }
        }
        float t_next;
        vec3 at, n_next;
        if (left_by_front && next_interface(p1, t1, t_next, at, n_next)) {
            n2 = n_next;
            dT = t_next;
            p2 = at;
        }
        if (dot(n2, n2) < 0.5) {
            nothing();
            return;
        }
        n2 = normalize(n2);
        // Leaving, or totally reflected and marched to the next interface
        // (issue 8: a tilted cube of IOR 1.5 sends over half the light it
        // takes in into total internal reflection at the first exit; an
        // exact trace of it puts 0.45 of the light on the floor with them
        // followed, 0.29 with them dropped). Up to 4 interfaces; the part
        // Fresnel reflects where the photon leaves is not followed.
        vec3 pos = p2, d_in = t1, n_here = n2, pos_next;
        float travelled = dT;
        bool leaves = false;
        for (int crossing = 0; crossing < 4; crossing++) {
            vec3 m = dot(d_in, n_here) > 0.0 ? -n_here : n_here;
            vec3 t2 = refract(d_in, m, ior);
            if (dot(t2, t2) > 0.0) {
                float f2 = fresnel_of(-dot(d_in, m), ior, ideal);
                flux *= (1.0 - f2) * exp(-absorption * travelled);
                dir = normalize(t2);
                origin = pos - m * eps;
                leaves = true;
                break;
            }
            // A total internal reflection just past the critical angle (n sin
            // theta below 1.1) is where the estimate's exit normal decides
            // between leaving and reflecting (a 1.15 sphere, which has no
            // such paths, showed them at its rim): such photons are dropped
            // as before; the rest are followed. Measured (caustic-region
            // rel_rmse; README): following them all took Fig. 24 f from
            // 0.226 to 0.326, with the band dropped to 0.150; the tilted
            // IOR 1.5 cube's floor light is 0.95 of an exact trace's either
            // way (0.59 with none followed).
            float cos_i = -dot(d_in, m);
            if (ior * sqrt(max(1.0 - cos_i * cos_i, 0.0)) < 1.1)
                break;
            d_in = reflect(d_in, m);
            float t;
            vec3 nn;
            if (!next_interface(pos, d_in, t, pos_next, nn) || dot(nn, nn) < 0.5)
                break;
            n_here = normalize(nn);
            pos = pos_next;
            travelled += t;
        }
        if (!leaves) {
            nothing();
            return;
        }
        }
    }
    float best = 1e30;
    int hit = -1;
    vec2 huv = vec2(0.0);
    for (int k = 0; k < u_impostor_count; k++) {
        vec2 kuv;
        float t = impostor_march(k, origin, dir, 32, u_iterations, kuv);
        if (t > 0.0 && t < best) {
            best = t;
            hit = k;
            huv = kuv;
        }
    }
    if (hit < 0) {
        nothing();
        return;
    }
    if (single && !is_mirror && u_reflect_glass == 0)
        flux *= exp(-absorption * best); // absorbed along the way in the water
    o_photon = vec4(huv, float(hit), 1.0);
    o_flux = vec4(flux, 1.0);
}
