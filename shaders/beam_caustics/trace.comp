#version 450 core
// Liktor & Dachsbacher 2011 §4.1 and §6: the edge rays of the projected
// grid. Each vertex of the finest lattice samples the light's view of the
// specular surfaces (the light-space G-buffer: here the refractors' depth
// layers, passes/helpers/layers.c, so the "two-sided refraction" of §6 follows the
// ray through every interface, with total internal reflection, instead of
// a distance impostor of the back faces), and keeps the transmitted ray
// where it leaves the last interface and the ray reflected off the first.
// Each ray's extrusion length is found by approximate ray tracing against
// the receivers (§4.3: a distance impostor around the refractors'
// centre, Szirmay-Kalos et al. 2005).
#include "common/frame.glsl"
#include "common/medium.glsl"
#include "common/shadows.glsl"
#include "layers/trace.glsl"
#include "beam_caustics/beams.glsl"
#include "beam_caustics/distance.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
// (u_light, u_light_ortho, u_jitter: BeamParams, beams.glsl)

// Where lattice vertex ij samples the light's view, in texels: the texel
// round(i (B - 1) / M) (the lattice spans the light's image), its centre
// moved by this frame's jitter when the pass accumulates over frames, kept
// inside the view.
vec2 vertex_position(ivec2 ij)
{
    float cell = float(u_layer_size.x - 1) / float(u_lattice);
    vec2 texel = floor(vec2(ij) * cell + 0.5);
    return clamp(texel + 0.5 + u_jitter * cell, vec2(0.5), vec2(u_layer_size) - 0.5);
}

void main()
{
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(ij, ivec2(u_lattice))))
        return;
    int idx = vertex_index(ij.x, ij.y);
    BeamVertex bv;
    bv.exit_pos = vec4(0.0);
    bv.exit_dir = vec4(0.0);
    bv.exit_weight = vec4(0.0);
    bv.refl_pos = vec4(0.0);
    bv.refl_dir = vec4(0.0);
    bv.refl_weight = vec4(0.0);
    bv.normal = vec4(0.0);
    bv.exit_sigma = vec4(0.0);
    vec2 at = vertex_position(ij);
    ivec2 p = ivec2(floor(at));
    uint flags = 0u;
    // A vertex just off the refractors' silhouette, with a neighbour on
    // them, is moved to the nearest texel on them towards that neighbour:
    // the cells across the silhouette then make beams up to it instead of
    // none (§4.2 refines there, but any finite lattice dropped a rim of the
    // light: an IOR-1.0001 ball lit only a polygon of its shadow).
    if (layer_count(p) == 0) {
        float best = 1e30;
        ivec2 found = p;
        for (int n = 0; n < 4; n++) {
            ivec2 nij = ij + ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1))[n];
            if (any(lessThan(nij, ivec2(0))) || any(greaterThan(nij, ivec2(u_lattice))))
                continue;
            ivec2 pn = ivec2(floor(vertex_position(nij)));
            if (layer_count(pn) == 0)
                continue;
            int span = max(abs(pn.x - p.x), abs(pn.y - p.y));
            for (int s = 1; s <= span; s++) {
                ivec2 q = p + ivec2(round(vec2(pn - p) * float(s) / float(span)));
                if (layer_count(q) > 0) {
                    float dist = length(vec2(q - p));
                    if (dist < best) {
                        best = dist;
                        found = q;
                    }
                    break;
                }
            }
        }
        if (best < 1e30) {
            p = found;
            at = vec2(found) + 0.5;
            flags |= VERTEX_SNAPPED;
        }
    }
    bool exists;
    float depth0 = layer_count(p) > 0 ? layer_depth_at(at, 0, exists) : 1.0;
    vec3 P0 = layer_point(at, depth0);
    vec3 d0 = u_light_ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(P0);
    bv.light_plane = u_light_ortho == 1 ? vec4(P0.xy, 0.0, 0.0) : vec4(d0.xy / max(-d0.z, 1e-6), 0.0, 0.0);
    if (layer_count(p) > 0) {
        flags |= VERTEX_SURFACE;
        mat3 to_world = mat3(u_layer_inv_view);
        GpuLight light = u_lights[u_light];
        // the light arriving at the first interface: spot cone and the medium on the way
        vec3 entry_world = (u_layer_inv_view * vec4(P0, 1.0)).xyz;
        vec3 w = vec3(1.0);
        vec3 to_light;
        float dist;
        if (u_light_ortho == 1) {
            to_light = -normalize(light.direction.xyz);
            dist = 1e30;
        } else {
            vec3 dl = light.position.xyz - entry_world;
            dist = length(dl);
            to_light = dl / max(dist, 1e-20);
            if (int(light.position.w + 0.5) == 2)
                w *= smoothstep(light.direction.w, max(light.intensity.w, light.direction.w + 1e-4),
                                dot(-to_light, normalize(light.direction.xyz)));
            // a point light's texels off the axis see less of the plane per solid angle: the
            // light-plane area (tangents) times cos^3 is the solid angle
            float c = max(-d0.z, 1e-6);
            w *= c * c * c;
        }
        w *= medium_transmittance_ray(entry_world, to_light, dist);
        LayerPath path = layer_trace_at(at, d0);
        vec3 n0 = normalize(to_world * path.normal0);
        // the panes between the light and the glass let (1 - F) x tint of
        // it through, from the light's shadow map where the pass reads one
        // (its pane filter), as the reference's photons cross them (issue 50)
        w *= pane_filter(u_light, entry_world, n0, to_light);
        bv.normal = vec4(n0, 0.0);
        vec3 reflected = normalize(to_world * reflect(d0, path.normal0));
        bv.refl_pos = vec4(entry_world, depth0);
        if (path.fresnel0 > 0.0) {
            flags |= VERTEX_REFLECTED;
            float len = extrusion_length(entry_world + reflected * (1e-4 * u_layer_extent), reflected);
            bv.refl_dir = vec4(reflected, len);
            bv.refl_weight = vec4(w * path.fresnel0, 0.0);
        }
        if (path.fresnel0 < 1.0 && path.entered && !path.capped) {
            flags |= VERTEX_TRANSMITTED;
            vec3 o = (u_layer_inv_view * vec4(path.origin, 1.0)).xyz;
            vec3 d = normalize(to_world * path.dir);
            bv.exit_pos = vec4(o, 0.0);
            float len = extrusion_length(o, d);
            bv.exit_dir = vec4(d, len);
            vec4 clip = u_view_proj * vec4(o + d * len, 1.0);
            if (len > 0.0 && clip.w > 0.0 && all(lessThanEqual(abs(clip.xy), vec2(clip.w))))
                flags |= VERTEX_SEEN;
            // the path's signature: rays through different interfaces do not share a beam
            bv.exit_weight = vec4(w * (1.0 - path.fresnel0) * path.throughput,
                                  float(path.interfaces + 64 * path.tir));
            bv.exit_sigma = vec4(layer_path_sigma(path), 0.0);
        }
    }
    bv.exit_pos.w = float(flags);
    beam_vertices[idx] = bv;
}
