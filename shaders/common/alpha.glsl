// glTF's alphaMode (struct material's alpha, alpha_cutoff, alpha_blend) at
// a fragment: the base colour's alpha (factor x COLOR_0 x texture) and the
// cut-out test on it. Shared by common/material.glsl (diffuse surfaces,
// thin glass, the shadow maps) and refraction's shaders (glass and
// mirrors: issue 50). The includer declares u_base_color_texture,
// u_texture_set[] and u_texture_transform[] (slot 0: the base colour) and
// v_texcoord0/1; the vertex shader passes v_color.
#ifndef ALPHA_GLSL
#define ALPHA_GLSL
uniform float u_alpha = 1.0;   // the base colour's alpha factor
uniform float u_alpha_cutoff;  // glTF alphaMode MASK: cut out below it; 0: opaque (struct material)
uniform int u_alpha_blend;     // glTF alphaMode BLEND: kept with probability alpha (an ordered dither)
in vec4 v_color;               // glTF's COLOR_0: it multiplies the base colour and its alpha ...
uniform int u_vertex_colors;   // ... where the mesh has one (an interpolated constant 1 is not always exactly 1)

// A cut-out (glTF alphaMode MASK): the surface is not there where the
// base colour's alpha (factor x texture) is below the cutoff. The
// reference cuts out the same texels (ref_scene.c's filter).
// BLEND, where a pass cannot blend (the shadow map, the distance map,
// impostors: shade blends, back to front), is a stochastic cut-out: a
// region keeps alpha of its texels by a 4 x 4 Bayer threshold over blocks
// of 4 x 4 texels (whole blocks: the shadow lookup filters depths
// bilinearly, which would smear a per-texel pattern into a whole shadow),
// which its 3 x 3 filter turns into a partial shadow; the reference keeps
// the surface per ray with probability alpha.
// The base colour's alpha: factor x texture.
float material_alpha()
{
    float a = u_vertex_colors == 1 ? u_alpha * v_color.a : u_alpha;
    if (u_texture_set[0] == 0)
        return a;
    vec3 q = vec3(u_texture_set[0] == 2 ? v_texcoord1 : v_texcoord0, 1.0);
    return a * texture(u_base_color_texture, vec2(dot(u_texture_transform[0], q), dot(u_texture_transform[1], q))).a;
}

bool material_cut_out()
{
    if (u_alpha_cutoff <= 0.0 && u_alpha_blend == 0)
        return false;
    float a = material_alpha();
    if (u_alpha_blend == 0)
        return a < u_alpha_cutoff;
    ivec2 q = (ivec2(gl_FragCoord.xy) >> 2) & 3; // blocks of 4 x 4 texels: depths filtered bilinearly stay whole
    int s = q.x ^ q.y; // the 4 x 4 Bayer index: bits of (x ^ y) and y interleaved, reversed
    int bayer = ((s & 1) << 3) | ((q.y & 1) << 2) | (((s >> 1) & 1) << 1) | ((q.y >> 1) & 1);
    return a <= (float(bayer) + 0.5) / 16.0;
}
#endif
