#ifndef SURFACE_NORMAL_GLSL
#define SURFACE_NORMAL_GLSL
// A surface's normal at uv from a normal buffer. Bilinear between texels
// that see one smooth surface; where the four texels around uv disagree by
// more than ~25 degrees (an edge of a faceted object, a cube's, or the
// silhouette, where a texel holds no surface) the nearest texel that holds
// a surface: blending across an edge made a texel-wide band of normals
// that belong to neither face (issue 8: lines along the TIR cube's edges).
vec3 surface_normal(sampler2D normals, vec2 uv)
{
    vec2 size = vec2(textureSize(normals, 0));
    vec2 f = uv * size - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 w = f - vec2(base);
    vec3 n[4];
    float cosine = 1.0;
    bool all_valid = true;
    for (int i = 0; i < 4; i++) {
        ivec2 q = clamp(base + ivec2(i & 1, i >> 1), ivec2(0), ivec2(size) - 1);
        n[i] = texelFetch(normals, q, 0).xyz;
        all_valid = all_valid && dot(n[i], n[i]) > 0.5;
    }
    if (all_valid) {
        for (int i = 1; i < 4; i++)
            cosine = min(cosine, dot(normalize(n[0]), normalize(n[i])));
        if (cosine > 0.9)
            return mix(mix(n[0], n[1], w.x), mix(n[2], n[3], w.x), w.y);
    }
    // the nearest texel holding a surface, by distance to uv
    float best = 1e30;
    vec3 pick = vec3(0.0);
    for (int i = 0; i < 4; i++) {
        vec2 d = vec2(i & 1, i >> 1) - w;
        float dd = dot(d, d);
        if (dot(n[i], n[i]) > 0.5 && dd < best) {
            best = dd;
            pick = n[i];
        }
    }
    return pick;
}
#endif
