// The shadow maps a pass reads (src/passes/helpers/shadow_inputs.c binds them):
// up to 4, 2D (directional and spot lights) or distance cube maps (point
// and linear lights), each covering a run of the frame's light entries.
uniform int u_shadow_total;
uniform int u_shadow_first[4];
uniform int u_shadow_count[4];
uniform int u_shadow_cube[4];
uniform mat4 u_shadow_matrix[4];
uniform vec4 u_shadow_params[4]; // range, bias, 1/size, 1: a thin-glass filter is bound
uniform sampler2D u_shadow_2d[4];
uniform samplerCube u_shadow_cubes[4];
uniform sampler2D u_shadow_filter[4]; // 2D maps: what thin-walled glass lets through (RGB), its depth (A)

// Fraction of light reaching p from the light of shadow map k (3x3 PCF).
float shadow_visibility(int k, vec3 p, vec3 n, vec3 to_light)
{
    float bias = u_shadow_params[k].y * (1.0 + 2.0 * (1.0 - abs(dot(n, to_light))));
    if (u_shadow_cube[k] == 1) {
        vec3 d = (u_shadow_matrix[k] * vec4(p, 1.0)).xyz; // p - light position
        float dist = length(d);
        float stored = texture(u_shadow_cubes[k], d).r * u_shadow_params[k].x;
        return dist - bias > stored ? 0.0 : 1.0;
    }
    vec4 c = u_shadow_matrix[k] * vec4(p + n * bias, 1.0);
    if (c.w <= 0.0)
        return 1.0;
    vec3 q = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))))
        return 1.0;
    q.z = min(q.z, 1.0); // past the far plane: behind whatever the map holds there
    float texel = u_shadow_params[k].z, lit = 0.0;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++)
            lit += q.z - 1e-5 > texture(u_shadow_2d[k], q.xy + vec2(x, y) * texel).r ? 0.0 : 1.0;
    return lit / 9.0;
}

// What thin-walled glass lets through towards light of map k at p: the
// product of the panes' (1 - F) x tint (shadow_map/thin_filter.frag) where
// p is behind the nearest of them, else 1. No filter: 1 (the scene has no
// thin glass, or the map is a cube map, which says so).
vec3 shadow_filter(int k, vec3 p, vec3 n, vec3 to_light)
{
    if (u_shadow_params[k].w < 0.5 || u_shadow_cube[k] == 1)
        return vec3(1.0);
    float bias = u_shadow_params[k].y * (1.0 + 2.0 * (1.0 - abs(dot(n, to_light))));
    vec4 c = u_shadow_matrix[k] * vec4(p + n * bias, 1.0);
    if (c.w <= 0.0)
        return vec3(1.0);
    vec3 q = c.xyz / c.w * 0.5 + 0.5;
    vec4 f = texture(u_shadow_filter[k], q.xy);
    return q.z > f.a ? f.rgb : vec3(1.0);
}

// What thin-walled glass lets through from `light` to p, where light meets
// glass, water or a mirror (a caustics pass's photon or beam: it takes the
// panes between the light and the refractor), from the maps of that light
// that the pass reads; 1 where none. Each map by a constant index: LLVM 15
// in llvmpipe failed to compile photon_caustics' trace shader with the
// sampler array indexed by a loop's counter ("Cannot select
// X86ISD::CVTP2SI"), which shade's lighting loop does not hit.
bool pane_map(int k, int light)
{
    return k < u_shadow_total && light >= u_shadow_first[k] && light < u_shadow_first[k] + u_shadow_count[k];
}
vec3 pane_filter(int light, vec3 p, vec3 n, vec3 to_light)
{
    vec3 f = vec3(1.0);
    if (pane_map(0, light))
        f *= shadow_filter(0, p, n, to_light);
    if (pane_map(1, light))
        f *= shadow_filter(1, p, n, to_light);
    if (pane_map(2, light))
        f *= shadow_filter(2, p, n, to_light);
    if (pane_map(3, light))
        f *= shadow_filter(3, p, n, to_light);
    return f;
}

// The light of `light` reaching p: the shadow maps' visibility x what thin
// glass lets through.
vec3 visibility_color(int light, vec3 p, vec3 n, vec3 to_light)
{
    for (int k = 0; k < u_shadow_total; k++)
        if (light >= u_shadow_first[k] && light < u_shadow_first[k] + u_shadow_count[k])
            return shadow_visibility(k, p, n, to_light) * shadow_filter(k, p, n, to_light);
    return vec3(1.0);
}

float visibility(int light, vec3 p, vec3 n, vec3 to_light)
{
    for (int k = 0; k < u_shadow_total; k++)
        if (light >= u_shadow_first[k] && light < u_shadow_first[k] + u_shadow_count[k])
            return shadow_visibility(k, p, n, to_light);
    return 1.0;
}
