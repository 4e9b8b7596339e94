#version 450 core
// Chaudhari 2008 §4.1 (Figs. 4.5-4.6): photons from the light's view of the
// refractors' depth layers, traced through every interface like the
// camera's rays (layers/trace.glsl), then in the camera's image of the
// receivers (Kruger et al. 2006's eye-space photon tracing, here a march
// against the receivers' depth, layers/scene_trace.glsl). Each photon's
// landing point and flux are stored for splat.comp, which sizes its
// footprint from its neighbours': layer 0 the light through the object,
// layer 1 the light reflected off its first interface.
#include "common/frame.glsl"
#include "layers/trace.glsl"
#include "layers/scene_trace.glsl"
#include "common/shadows.glsl"
uniform sampler2D u_receiver_normal;
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f) uniform writeonly image2DArray u_hits;
layout(rgba32f) uniform writeonly image2DArray u_photons;
// (u_light, u_light_ortho, u_texel_area, u_texel_tan, u_jitter, u_fixed_point: landed.glsl's block)
#include "layered_caustics/landed.glsl"

// A photon that lands: its brightest channel's counts to the light landed.
void count_landed(vec3 flux)
{
    atomicAdd(landed_units, uint(ceil(max(max(flux.r, flux.g), flux.b) * u_fixed_point)));
}

// Where the photon (world o, d) lands on a receiver the camera sees.
bool land(vec3 o, vec3 d, out vec3 at, out ivec2 px)
{
    float t;
    if (!scene_trace_at(o, d, px, t))
        return false;
    vec3 n = texelFetch(u_receiver_normal, px, 0).xyz;
    at = o + d * t;
    // light arriving at the side the camera does not see lights nothing it sees
    return dot(n, d) < 0.0;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, u_layer_size)))
        return;
    // w: 1 landed, 0 lost on the way, -1 the ray missed the refractors
    // (splat.comp's open_beyond: the silhouette lies beside it)
    float missed = layer_count(p) == 0 ? -1.0 : 0.0;
    imageStore(u_hits, ivec3(p, 0), vec4(0.0, 0.0, 0.0, missed));
    imageStore(u_hits, ivec3(p, 1), vec4(0.0, 0.0, 0.0, missed));
    if (layer_count(p) == 0)
        return;
    // the photon's start in the light's image: its texel's centre, moved by
    // this frame's jitter when the pass accumulates over frames
    vec2 at_px = vec2(p) + 0.5 + u_jitter;
    bool exists;
    vec3 P0 = layer_point(at_px, layer_depth_at(at_px, 0, exists));
    vec3 d0 = u_light_ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(P0);
    // the flux through this texel, before the surface
    GpuLight light = u_lights[u_light];
    vec3 flux;
    if (u_light_ortho == 1) {
        flux = light.intensity.rgb * u_texel_area;
    } else {
        // the texel's solid angle: side^2 cos^3 (a texel off the axis)
        float c = max(-d0.z, 1e-6);
        flux = light.intensity.rgb * u_texel_tan * u_texel_tan * c * c * c;
        if (int(light.position.w + 0.5) == 2) {
            vec3 world_d = normalize(mat3(u_layer_inv_view) * d0);
            flux *= smoothstep(light.direction.w, max(light.intensity.w, light.direction.w + 1e-4),
                               dot(world_d, normalize(light.direction.xyz)));
        }
    }
    LayerPath path = layer_trace_at(at_px, d0);
    mat3 to_world = mat3(u_layer_inv_view);
    vec3 entry = (u_layer_inv_view * vec4(path.entry, 1.0)).xyz;
    // the panes between the light and the glass let (1 - F) x tint of it
    // through, from the light's shadow map where the pass reads one (its
    // pane filter, shadow_map/thin_filter.frag), as the reference's photons
    // cross them (issue 50)
    vec3 to_light = u_light_ortho == 1 ? -normalize(light.direction.xyz) : normalize(light.position.xyz - entry);
    flux *= pane_filter(u_light, entry, normalize(to_world * path.normal0), to_light);
    vec3 reflected = normalize(to_world * reflect(d0, path.normal0));
    vec3 at;
    ivec2 px;
    if (path.fresnel0 > 0.0 && land(entry + reflected * (1e-4 * u_layer_extent), reflected, at, px)) {
        imageStore(u_hits, ivec3(p, 1), vec4(at, 1.0));
        imageStore(u_photons, ivec3(p, 1), vec4(flux * path.fresnel0, 0.0));
        count_landed(flux * path.fresnel0);
    }
    vec3 exit = (u_layer_inv_view * vec4(path.origin, 1.0)).xyz;
    if (path.fresnel0 < 1.0 && land(exit, normalize(to_world * path.dir), at, px)) {
        imageStore(u_hits, ivec3(p, 0), vec4(at, 1.0));
        // a receiver inside the medium (a floor under water): absorbed on the way there too
        vec3 absorbed = layer_path_absorption(path, length(at - exit));
        vec3 carried = flux * (1.0 - path.fresnel0) * path.throughput * absorbed;
        imageStore(u_photons, ivec3(p, 0), vec4(carried, 0.0));
        count_landed(carried);
    }
}
