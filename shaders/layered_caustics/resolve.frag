#version 450 core
// Flux per pixel -> irradiance on the receiver: divided by the area the
// pixel covers on the surface (its footprint at that depth over the cosine
// between the view ray and the normal).
#include "common/frame.glsl"
uniform sampler2D u_receiver_normal;
uniform sampler2D u_receiver_depth;
layout(r32ui) uniform readonly uimage2DArray u_flux;
#include "layered_caustics/landed.glsl"
layout(location = 0) out vec4 o_irradiance;
// Where pixel corner c (window coordinates) looks, on the plane through x
// with normal n; false where its ray runs along or away from the plane.
bool corner_on_plane(vec2 c, vec3 x, vec3 n, out vec3 at)
{
    vec2 ndc = c * u_viewport.zw * 2.0 - 1.0;
    vec4 a = u_inv_view_proj * vec4(ndc, -1.0, 1.0), b = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w, d = b.xyz / b.w - o;
    float dn = dot(d, n);
    float t = abs(dn) > 1e-20 ? dot(x - o, n) / dn : -1.0;
    at = o + d * t;
    return t > 0.0;
}

// The area pixel p's four corner rays span on the plane through x with
// normal n (two triangles' worth: half the cross product of the quad's
// diagonals), or 0 where a corner's ray misses the plane.
float pixel_quad_area(ivec2 p, vec3 x, vec3 n)
{
    vec3 c0, c1, c2, c3;
    vec2 q = vec2(p);
    if (!corner_on_plane(q, x, n, c0) || !corner_on_plane(q + vec2(1.0, 0.0), x, n, c1) ||
        !corner_on_plane(q + vec2(1.0, 1.0), x, n, c2) || !corner_on_plane(q + vec2(0.0, 1.0), x, n, c3))
        return 0.0;
    return 0.5 * length(cross(c2 - c0, c3 - c1));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 n = texelFetch(u_receiver_normal, p, 0);
    if (n.w < 0.5) {
        o_irradiance = vec4(0.0);
        return;
    }
    float d = texelFetch(u_receiver_depth, p, 0).r;
    vec2 ndc = (vec2(p) + 0.5) * u_viewport.zw * 2.0 - 1.0;
    vec4 w = u_inv_view_proj * vec4(ndc, d * 2.0 - 1.0, 1.0);
    vec3 x = w.xyz / w.w;
    vec3 v = view_direction(x);
    float side = camera_is_ortho() ? u_pixel_size : view_depth(d) * u_pixel_tan;
    // the pixel's footprint on the surface: its solid angle side^2 cos^3 /
    // depth^2 (a ray off the axis) times the squared distance along the ray
    // (depth / cos) over the cosine at the surface: side^2 cos / cos_n
    float cos_axis = camera_is_ortho() ? 1.0 : max(dot(v, camera_forward()), 1e-3);
    float area = side * side * cos_axis / max(abs(dot(v, n.xyz)), 0.05);
    // ... which holds where the pixel is small against how fast depth and
    // angle change across it. Far off the axis of a very wide view (174
    // degrees) they change across one pixel, and the centre's estimate read
    // a flat-water floor 27% bright in the corners: a perspective pixel's
    // area is where its four corner rays meet the surface's tangent plane
    // (the same to 4 digits elsewhere; the estimate where a corner misses).
    float exact = camera_is_ortho() ? 0.0 : pixel_quad_area(p, x, n.xyz);
    if (exact > 0.0)
        area = exact;
    vec3 flux = vec3(imageLoad(u_flux, ivec3(p, 0)).r, imageLoad(u_flux, ivec3(p, 1)).r,
                     imageLoad(u_flux, ivec3(p, 2)).r) / landed_fixed_point();
    o_irradiance = vec4(flux / max(area, 1e-20), 1.0);
}
