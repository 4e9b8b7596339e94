// A normal map's normal, for every program that maps one: the diffuse
// surfaces' (common/material.glsl) and the glass and mirrors refraction
// draws (refraction/surfaces.frag, refract.frag). The reference's twin is
// ref_material.c's mapped_normal.
in vec4 v_tangent; // a normal map's tangent, interpolated (world xyz) ...
uniform int u_has_tangents; // ... where the mesh has them (glTF's TANGENT, or made at load)

// A tangent-space normal map's normal for the face-forward normal n at
// world point p: the map `m` (texels * 2 - 1) read at uv, scaled by `scale`.
// The tangent is the mesh's interpolated tangent where it has them (glTF's
// TANGENT, or made per vertex at load: smooth across a curved mesh), else
// the direction of increasing u
// on the triangle (solved from the screen derivatives of p and uv, exact for
// a flat triangle), made perpendicular to n; the bitangent is n x t, turned
// to the side of decreasing v (glTF's v runs down the image, and a normal
// map's green is up it): where the uv mapping is mirrored that is -(n x t),
// the handedness MikkTSpace stores in TANGENT's w (glTF's bitangent =
// cross(normal, tangent.xyz) * w; NormalTangentMirrorTest's mirrored
// bumps). A degenerate uv mapping (zero area in uv) leaves n as
// it is. Call in uniform control flow.
vec3 material_mapped_normal(vec3 n, vec3 p, vec2 uv, vec3 m, float scale)
{
    vec3 dp1 = dFdx(p), dp2 = dFdy(p);
    vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
    float det = duv1.x * duv2.y - duv1.y * duv2.x;
    vec3 pu = dp1 * duv2.y - dp2 * duv1.y; // (dp/du) * det
    vec3 pv = dp2 * duv1.x - dp1 * duv2.x; // (dp/dv) * det
    vec3 t = pu - n * dot(n, pu);
    float len = length(t);
    if (!(abs(det) > 1e-20) || !(len > 1e-20 * max(abs(det), 1e-20)))
        return n;
    t = t * (sign(det) / len);
    // The mesh's tangent where it has one: smooth across the triangles (the
    // side of increasing u, as pu; made perpendicular to n)
    vec3 tv = u_has_tangents == 1 ? v_tangent.xyz - n * dot(n, v_tangent.xyz) : vec3(0.0);
    if (dot(tv, tv) > 1e-12)
        t = normalize(tv);
    vec3 b = cross(n, t);
    if (dot(b, pv) * det > 0.0)
        b = -b; // a mirrored mapping: v runs the other way round n
    vec3 mapped = t * (m.x * scale) + b * (m.y * scale) + n * m.z;
    float ml = length(mapped);
    return ml > 1e-12 ? mapped / ml : n;
}

