#version 450 core
// Liktor & Dachsbacher 2011 §5: what one beam adds at one pixel.
// - Volume caustics (§5.1-5.2): the view ray meets the beam in the scan
//   plane n_p = r x (r x n) (Ernst et al. 2005), whose intersections with
//   the three edge rays form a triangle the ray crosses over Delta x; one
//   sample at the midpoint (u_samples along the interval in a density
//   grid, §8's smoke) gives L = Delta x e^(-sigma_t (s1 + s2)) sigma_s
//   p(w . w') L_in, with the flux density from the area function A(y).
//   The interval is clipped at the receiver's depth: the "soft clipping" of
//   §5.2 is exact here (no depth test, so nothing pops where a beam enters
//   a surface).
// - Surface caustics (§5.3): the receiver the camera sees at this pixel is
//   tested against the beam's cross-section at its height; inside, its
//   irradiance is the flux density there (barycentric weights of the edge
//   rays, A(y)) times the cosine at the receiver.
// The beam's flux is the light's intensity times its base's area on the
// light's image plane times the edge rays' weights; a focus (A -> 0) is
// bounded by the builder's floor on |A| (at most u_max_focus times the
// density at either end of the beam).
#include "common/frame.glsl"
#include "common/medium.glsl"
#include "beam_caustics/beams.glsl"
flat in int v_beam;
uniform sampler2D u_scene_depth;
uniform sampler2D u_scene_normal; // world normal, w = 1 on a receiver
// (u_light, u_samples, u_surface, u_smooth: BeamParams, beams.glsl)
layout(location = 0) out vec4 o_inscatter;
layout(location = 1) out vec4 o_irradiance;

Beam b;

float area_at(float y) { return max(0.5 * abs(b.area.x + b.area.y * y + b.area.z * y * y), b.area.w); }

// Barycentric weights of x in the beam's cross-section at height y (x on it).
vec3 section_weights(vec3 x, float y, out bool ok)
{
    vec3 n = b.n.xyz;
    vec3 q0 = b.v[0].xyz + b.d[0].xyz * y, q1 = b.v[1].xyz + b.d[1].xyz * y, q2 = b.v[2].xyz + b.d[2].xyz * y;
    vec3 e1 = q1 - q0, e2 = q2 - q0, ep = x - q0;
    float den = dot(cross(e1, e2), n);
    ok = abs(den) > 1e-30;
    if (!ok)
        return vec3(1.0 / 3.0);
    float b1 = dot(cross(ep, e2), n) / den, b2 = dot(cross(e1, ep), n) / den;
    return vec3(1.0 - b1 - b2, b1, b2);
}

// Beer-Lambert inside the refractor the beam runs in from its base to height
// y (|dd| y along the ray, dot(dd, n) = 1, less the stretch behind the exits
// where build.comp set the base): water over its floor, whose
// light is absorbed on the way down as much as in the glass the layers bound
// (§4.1 ends the beams at the receivers; the paper's glass has no receiver
// inside it, so it says nothing of absorption after the last interface).
vec3 beam_absorption(vec3 dd, float y, vec3 w)
{
    float behind = dot(w, vec3(b.d[0].w, b.d[1].w, b.d[2].w));
    return exp(-b.sigma.rgb * max(length(dd) * y - behind, 0.0));
}

// The flux density (per unit area across the rays) at height y with
// weights w, its direction, and the beam's own medium path from the base.
vec3 density_at(vec3 x, float y, vec3 w, out vec3 dir, out float cos_base)
{
    vec3 dd = w.x * b.d[0].xyz + w.y * b.d[1].xyz + w.z * b.d[2].xyz; // dot(dd, n) = 1
    float len = max(length(dd), 1.0);
    dir = dd / len;
    cos_base = 1.0 / len;
    vec3 weight = w.x * b.weight[0].rgb + w.y * b.weight[1].rgb + w.z * b.weight[2].rgb;
    vec3 flux = u_lights[u_light].intensity.rgb * weight * b.info.x;
    return flux / area_at(y) / cos_base * medium_transmittance(x - dd * y, x) * beam_absorption(dd, y, w);
}

// The flux density across the rays (per unit light-plane area and
// intensity) along edge ray k where it reaches height y: averaged over the
// beams that share that ray (the lattice's adjacency lists), as Ernst et
// al. 2005 average one area function per vertex, so that neighbouring
// beams agree along their shared edges.
float edge_density(int k, float y)
{
    vec3 x = b.v[k].xyz + b.d[k].xyz * y;
    vec3 dir = normalize(b.d[k].xyz);
    uint base = b.corners[k] * uint(ADJACENCY_STRIDE);
    uint count = min(adjacency[base], uint(ADJACENCY_SLOTS));
    // the neighbours' flux over their cross-sections across the ray there:
    // averaging the areas, as Ernst et al. do, not the densities (whose
    // average is pulled up by any one neighbour near its own focus)
    float flux = 0.0, area = 0.0;
    for (uint i = 0u; i < count; i++) {
        uint o = adjacency[base + 1u + i];
        if (beams[o].info.w != b.info.w)
            continue; // a reflected beam beside a transmitted one, or the other way round
        vec3 no = beams[o].n.xyz;
        vec4 ca = beams[o].area;
        float yo = dot(x - beams[o].v[0].xyz, no);
        float ao = max(0.5 * abs(ca.x + ca.y * yo + ca.z * yo * yo), ca.w);
        flux += beams[o].info.x;
        area += ao * max(dot(dir, no), 1e-3);
    }
    return area > 0.0 ? flux / area : b.info.x / (area_at(y) * max(dot(dir, b.n.xyz), 1e-3));
}

void main()
{
    o_inscatter = vec4(0.0);
    o_irradiance = vec4(0.0);
    b = beams[v_beam];
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 ndc = gl_FragCoord.xy * u_viewport.zw * 2.0 - 1.0;
    vec4 ha = u_inv_view_proj * vec4(ndc, -1.0, 1.0), hb = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 o = ha.xyz / ha.w, r = normalize(hb.xyz / hb.w - o);
    if (!camera_is_ortho())
        o = u_camera_pos.xyz;
    float depth = texelFetch(u_scene_depth, px, 0).r, t_surface = 1e30;
    vec3 P = vec3(0.0);
    if (depth < 1.0) {
        vec4 hp = u_inv_view_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        P = hp.xyz / hp.w;
        t_surface = max(dot(P - o, r), 0.0);
    }
    vec3 n = b.n.xyz;
    float top = b.n.w;

    // surface caustics (§5.3)
    vec4 receiver = texelFetch(u_scene_normal, px, 0);
    if (u_surface == 1 && depth < 1.0 && receiver.w > 0.5) {
        float y = dot(P - b.v[0].xyz, n);
        bool ok;
        vec3 w = section_weights(P, y, ok);
        float y_end = dot(w, vec3(b.v[0].w, b.v[1].w, b.v[2].w));
        float slack = 1e-3 * top;
        if (ok && y >= 0.0 && y <= y_end + slack && all(greaterThanEqual(w, vec3(0.0)))) {
            vec3 dir;
            float cos_base;
            vec3 e = density_at(P, y, w, dir, cos_base);
            if (u_smooth == 1) {
                vec3 dd = w.x * b.d[0].xyz + w.y * b.d[1].xyz + w.z * b.d[2].xyz;
                vec3 flux = w.x * b.weight[0].rgb * edge_density(0, y) + w.y * b.weight[1].rgb * edge_density(1, y) +
                            w.z * b.weight[2].rgb * edge_density(2, y);
                e = u_lights[u_light].intensity.rgb * flux * medium_transmittance(P - dd * y, P) *
                    beam_absorption(dd, y, w);
            }
            float cos_r = -dot(dir, receiver.xyz);
            if (cos_r > 0.0)
                o_irradiance = vec4(e * cos_r, 0.0);
        }
    }

    // volume caustics (§5.1-5.2)
    if (u_medium == 0)
        return;
    vec3 np = cross(r, cross(r, n));
    if (dot(np, np) < 1e-12) {
        // the view ray along the beam: any plane holding the ray will do
        vec3 axis = abs(r.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
        np = cross(r, axis);
    }
    np = normalize(np);
    vec3 p[3];
    for (int i = 0; i < 3; i++) {
        float dn = dot(b.d[i].xyz, np);
        if (abs(dn) < 1e-12)
            return; // an edge in the scan plane: the section is degenerate here
        p[i] = b.v[i].xyz + b.d[i].xyz * (dot(o - b.v[i].xyz, np) / dn);
    }
    float t_in = 1e30, t_out = -1e30;
    for (int i = 0; i < 3; i++) {
        vec3 pa = p[i], e = p[(i + 1) % 3] - pa;
        float den = dot(cross(r, e), np);
        if (abs(den) < 1e-20)
            continue;
        float t = dot(cross(pa - o, e), np) / den, u = dot(cross(pa - o, r), np) / den;
        if (u >= 0.0 && u <= 1.0) {
            t_in = min(t_in, t);
            t_out = max(t_out, t);
        }
    }
    if (!(t_out > t_in))
        return;
    // the beam's height range along the ray, the eye, the receiver, the medium's box
    float y_o = dot(o - b.v[0].xyz, n), r_n = dot(r, n);
    if (abs(r_n) > 1e-12) {
        float ta = (0.0 - y_o) / r_n, tb = (top - y_o) / r_n;
        t_in = max(t_in, min(ta, tb));
        t_out = min(t_out, max(ta, tb));
    } else if (y_o < 0.0 || y_o > top) {
        return;
    }
    float m0, m1;
    if (!medium_clip(o, r, min(t_surface, t_out), m0, m1))
        return;
    t_in = max(max(t_in, m0), 0.0);
    t_out = min(t_out, m1);
    if (!(t_out > t_in))
        return;
    int samples = max(u_samples, 1);
    float dt = (t_out - t_in) / float(samples);
    vec3 sum = vec3(0.0);
    for (int s = 0; s < samples; s++) {
        float t = t_in + (float(s) + 0.5) * dt;
        vec3 x = o + r * t;
        float y = y_o + r_n * t;
        bool ok;
        vec3 w = section_weights(x, y, ok);
        // the scan triangle's edges are straight, the beam's are not: a sample
        // just outside the beam is moved onto its side, one far outside (the
        // scan triangle strayed from the beam) adds nothing
        if (!ok || min(w.x, min(w.y, w.z)) < -0.1)
            continue;
        w = max(w, vec3(0.0));
        w /= max(w.x + w.y + w.z, 1e-20);
        if (y > dot(w, vec3(b.v[0].w, b.v[1].w, b.v[2].w)))
            continue;
        float rho = medium_density(x);
        if (rho <= 0.0)
            continue;
        vec3 dir;
        float cos_base;
        vec3 e = density_at(x, y, w, dir, cos_base);
        sum += u_medium_sigma_s * rho * medium_phase(dot(dir, -r)) * e * medium_transmittance(o, x);
    }
    o_inscatter = vec4(sum * dt, 0.0);
}
