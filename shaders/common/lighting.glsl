// Direct light from the frame's light list, in physical units: point and
// spot intensities in W/sr (irradiance I cos / r^2), directional in W/m^2.

// Irradiance from light `i` on a surface facing it (no cosine): what a
// point in a medium receives; `to_light` receives the unit direction
// towards the light and `dist` its distance.
vec3 light_arrival(int i, vec3 p, out vec3 to_light, out float dist)
{
    GpuLight l = u_lights[i];
    int kind = int(l.position.w + 0.5);
    if (kind == 1) {
        to_light = -normalize(l.direction.xyz);
        dist = 1e30;
        return l.intensity.rgb;
    }
    vec3 d = l.position.xyz - p;
    float d2 = max(dot(d, d), 1e-8);
    dist = sqrt(d2);
    to_light = d / dist;
    vec3 e = l.intensity.rgb / d2;
    if (kind == 2) {
        float c = dot(-to_light, normalize(l.direction.xyz));
        e *= smoothstep(l.direction.w, max(l.intensity.w, l.direction.w + 1e-4), c);
    }
    return e;
}

// Irradiance at `p` with normal `n` from light `i`, unshadowed; `to_light`
// receives the unit direction towards the light and `dist` its distance.
vec3 light_irradiance(int i, vec3 p, vec3 n, out vec3 to_light, out float dist)
{
    return light_arrival(i, p, to_light, dist) * max(dot(n, to_light), 0.0);
}
