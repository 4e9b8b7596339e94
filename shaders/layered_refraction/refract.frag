#version 450 core
// Chaudhari 2008 §3.6-3.8 per pixel of the refractors' first layer: the
// camera's ray traced through every layer (layers/trace.glsl); the light
// that leaves along it, times the Fresnel transmissions and absorption on
// the way, plus the reflection at the first interface.
#include "common/frame.glsl"
// LAYER_TRACE_SPLIT (defined by the pass where `internal` > 0): the part an
// exit reflects back inside is marched again
#include "layers/trace.glsl"
#include "layers/scene_trace.glsl"
#include "impostors/impostors.glsl"
uniform int u_correction; // Fig. 16's iterations for the impostor lookup
uniform sampler2D u_scene;
// The pass's values (issue 54: one block, mirrored by struct layered_refraction_params)
layout(std140) uniform LayeredRefractionParams {
    int u_lookup_scene; // 1: a leaving ray searches the input image, then the environment
    int u_reflection;   // the Fresnel-weighted reflection at the first interface
    int u_internal;     // marches of the light exits reflect back inside (0: the thesis's one path)
    int u_camera_ortho;
};
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_info; // layers, dropped, interfaces, total internal reflections (+100: capped)

// What a ray from world point o along d sees: the scene behind the glass
// in the input image, else an impostor (off screen), else the environment.
vec3 look(vec3 o, vec3 d)
{
    ivec2 px;
    if (u_lookup_scene == 1 && scene_trace(o, d, px))
        return texelFetch(u_scene, px, 0).rgb;
    vec3 c;
    if (u_lookup_scene == 1 && impostor_lookup(o, d, u_correction, c))
        return c;
    return environment_radiance(d);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    uvec2 info = texelFetch(u_layer_info, p, 0).rg;
    if (info.r == 0u)
        discard;
    float d0 = layer_depth(p, 0);
    // an opaque object in front of the refractor keeps the input's pixel
    float sd = texelFetch(u_scene_depth, p, 0).r;
    if (sd < 1.0 && view_depth(sd) < d0 * (1.0 - 1e-4) - 1e-4)
        discard;
    vec3 P0 = layer_point(vec2(p) + 0.5, d0);
    vec3 d = u_camera_ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(P0);
    LayerPath path = layer_trace(p, d);
    mat3 to_world = mat3(u_layer_inv_view);
    vec3 exit_o = (u_layer_inv_view * vec4(path.origin, 1.0)).xyz;
    vec3 exit_d = normalize(to_world * path.dir);
    vec3 entry = (u_layer_inv_view * vec4(path.entry, 1.0)).xyz;
    vec3 reflected = normalize(to_world * reflect(d, path.normal0));
    vec3 color = vec3(0.0);
    if (path.fresnel0 < 1.0)
        color += (1.0 - path.fresnel0) * path.throughput * look(exit_o, exit_d);
    // The part reflected back inside where the path first left (the thesis
    // drops it; after a total internal reflection, near the critical angle,
    // it is most of the light: the IOR 2.42 cube with Fresnel came out dark
    // in every such pixel): more marches, each from where the last one
    // first left, while a hundredth of the light is in the part reflected.
    // Stopping at a tenth dropped up to 10% of every such pixel (issue 52,
    // case 12: 179 of the cube's 2,051 pixels within 0.02 of the exact
    // trace; 1,150 now, the pass 1.2x the time there). Glass under IOR 2
    // compiles no marches (layered_refraction.c), so pays nothing.
#ifdef LAYER_TRACE_SPLIT
    LayerPath from = path;
    for (int k = 0; k < u_internal && from.fresnel0 < 1.0 && from.split &&
                    max(from.split_weight.r, max(from.split_weight.g, from.split_weight.b)) > 0.01; k++) {
        LayerPath next = layer_continue(from);
        vec3 next_o = (u_layer_inv_view * vec4(next.origin, 1.0)).xyz;
        color += (1.0 - path.fresnel0) * next.throughput * look(next_o, normalize(to_world * next.dir));
        from = next;
    }
#endif
    if (u_reflection == 1 || path.fresnel0 >= 1.0)
        color += path.fresnel0 * look(entry + reflected * (1e-4 * u_layer_extent), reflected);
    o_color = vec4(color, 1.0);
    o_info = vec4(float(info.r), float(info.g), float(path.interfaces), float(path.tir) + (path.capped ? 100.0 : 0.0));
}
