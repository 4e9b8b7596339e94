#ifndef SCENE_BOUNDS_GLSL
#define SCENE_BOUNDS_GLSL
// The diffuse objects' bounding box (layers_bind_scene_trace sets it): a ray that
// leaves the refractors can meet nothing outside it, so the searches of
// what it sees (the screen-space march, the distance map's walk) stop
// where it leaves the box, and a ray that misses the box sees the
// environment without any search. (On llvmpipe those searches were most of
// the refraction pass's time, and most of it was spent on rays that go to
// the sky.) Unset, the box is everything.
uniform vec3 u_scene_lo = vec3(-1e30);
uniform vec3 u_scene_hi = vec3(1e30);

// The ray's parameter interval inside the box (grown by a thousandth of
// its diagonal); false when it misses the box or the box is behind it.
bool scene_bounds_segment(vec3 o, vec3 d, out float t_enter, out float t_exit)
{
    vec3 grow = vec3(1e-3 * min(length(u_scene_hi - u_scene_lo), 1e30) + 1e-4);
    vec3 lo = u_scene_lo - grow, hi = u_scene_hi + grow;
    vec3 inv = 1.0 / mix(d, vec3(1e-20), equal(d, vec3(0.0)));
    vec3 ta = (lo - o) * inv, tb = (hi - o) * inv;
    vec3 tmin = min(ta, tb), tmax = max(ta, tb);
    t_enter = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
    t_exit = min(min(tmax.x, tmax.y), tmax.z);
    return t_enter <= t_exit;
}
#endif
