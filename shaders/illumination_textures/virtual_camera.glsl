// The virtual camera of the illumination textures (Iwasaki et al. §4.2):
// an orthographic view along the average transmitted direction D, with
// in-plane axes U, V; a point's texture coordinates and its depth along D.
uniform vec3 u_vc_d;
uniform vec3 u_vc_u;
uniform vec3 u_vc_v;
uniform vec3 u_vc_center;  // (dot(c, U), dot(c, V), 0): the square's centre in the plane
uniform float u_vc_half;   // half its side
uniform vec2 u_vc_depth;   // the depth range drawn: [near, far] along D

vec2 vc_uv(vec3 p) { return vec2(dot(p, u_vc_u) - u_vc_center.x, dot(p, u_vc_v) - u_vc_center.y) / (2.0 * u_vc_half) + 0.5; }
float vc_depth(vec3 p) { return dot(p, u_vc_d); }
vec4 vc_clip(vec3 p)
{
    float z = (vc_depth(p) - u_vc_depth.x) / max(u_vc_depth.y - u_vc_depth.x, 1e-20) * 2.0 - 1.0;
    return vec4(vc_uv(p) * 2.0 - 1.0, z, 1.0);
}
