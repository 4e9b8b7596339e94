#ifndef DEPTH_MARCH_GLSL
#define DEPTH_MARCH_GLSL
// The next interface of a ray inside the specular objects, found in a view
// that has their front and back depth buffers (the camera's in refraction,
// the light's in photon_caustics; issue 8): a point is inside while its
// window depth lies between the front and the back depth at its texel; the
// first of STEPS even steps outside is bisected, and which bound it crossed
// says which surface the ray leaves through (the side of a silhouette: the
// back one). Requires, before the include: vec3 project(vec3 world) -> (uv,
// window depth), and the samplers u_front_depth and u_back_depth. `reach`:
// how far to march (the refractors' extent); false: still inside after it.
// t_inside is the last point inside, where the surface's normal is read.
bool depth_march(vec3 o, vec3 d, float reach, out float t_exit, out float t_inside, out bool through_back)
{
    const int STEPS = 24;
    float lo = 0.0, hi = -1.0;
    through_back = true;
    t_exit = t_inside = 0.0;
    for (int i = 1; i <= STEPS; i++) {
        float t = reach * float(i) / float(STEPS);
        vec3 q = project(o + t * d);
        bool off = any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)));
        float zf = off ? 1.0 : texture(u_front_depth, q.xy).r, zb = off ? 1.0 : texture(u_back_depth, q.xy).r;
        if (zf >= 1.0 || q.z < zf || q.z > zb) {
            hi = t;
            through_back = zf >= 1.0 || q.z > zb;
            break;
        }
        lo = t;
    }
    if (hi < 0.0)
        return false;
    for (int k = 0; k < 8; k++) {
        float t = 0.5 * (lo + hi);
        vec3 q = project(o + t * d);
        float zf = texture(u_front_depth, q.xy).r, zb = texture(u_back_depth, q.xy).r;
        if (zf >= 1.0 || q.z < zf || q.z > zb) {
            hi = t;
            through_back = zf >= 1.0 || q.z > zb;
        } else {
            lo = t;
        }
    }
    t_exit = hi;
    t_inside = lo;
    return true;
}
#endif
