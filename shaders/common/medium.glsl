// The scene's participating medium (src/graph/medium_gpu.c sets these): a
// box of sigma_s, sigma_t = sigma_s + sigma_a at density 1, a density that
// is a constant or a grid (trilinear, a 3D texture), and a Henyey-Greenstein
// phase function, as the reference's (src/reference/ref_media.c).
uniform int u_medium;          // 0: no medium (transmittance 1, no scattering)
uniform vec3 u_medium_lo, u_medium_hi;
uniform vec3 u_medium_sigma_s, u_medium_sigma_t;
uniform float u_medium_g;
uniform float u_medium_density; // a homogeneous medium's density
uniform int u_medium_grid;      // 1: the density grid below
uniform vec3 u_medium_grid_scale, u_medium_grid_offset; // texture coordinate = p * scale + offset
uniform sampler3D u_medium_texture;

const int MEDIUM_STEPS = 16; // midpoint steps of a transmittance through a density grid

// The part [t0, t1] of the ray o + t d (0 <= t <= tmax) inside the box.
bool medium_clip(vec3 o, vec3 d, float tmax, out float t0, out float t1)
{
    t0 = 0.0;
    t1 = tmax;
    if (u_medium == 0)
        return false;
    for (int a = 0; a < 3; a++) {
        if (abs(d[a]) < 1e-20) {
            if (o[a] < u_medium_lo[a] || o[a] > u_medium_hi[a])
                return false;
            continue;
        }
        float ta = (u_medium_lo[a] - o[a]) / d[a], tb = (u_medium_hi[a] - o[a]) / d[a];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    return t1 > t0;
}

float medium_density(vec3 p)
{
    if (u_medium == 0 || any(lessThan(p, u_medium_lo)) || any(greaterThan(p, u_medium_hi)))
        return 0.0;
    return u_medium_grid == 1 ? texture(u_medium_texture, p * u_medium_grid_scale + u_medium_grid_offset).r
                              : u_medium_density;
}

// The optical depth (sigma_t times the density integrated) along o + t d,
// 0 <= t <= tmax (d need not be unit: t is in its units).
vec3 medium_optical_depth(vec3 o, vec3 d, float tmax)
{
    float t0, t1;
    if (!medium_clip(o, d, tmax, t0, t1))
        return vec3(0.0);
    float len = (t1 - t0) * length(d);
    if (u_medium_grid == 0)
        return u_medium_sigma_t * (u_medium_density * len);
    float sum = 0.0;
    for (int i = 0; i < MEDIUM_STEPS; i++)
        sum += medium_density(o + d * mix(t0, t1, (float(i) + 0.5) / float(MEDIUM_STEPS)));
    return u_medium_sigma_t * (sum / float(MEDIUM_STEPS) * len);
}

// Transmittance between a and b, and along a ray.
vec3 medium_transmittance(vec3 a, vec3 b) { return exp(-medium_optical_depth(a, b - a, 1.0)); }
vec3 medium_transmittance_ray(vec3 o, vec3 d, float tmax) { return exp(-medium_optical_depth(o, d, tmax)); }

// Henyey-Greenstein, per steradian; cos_theta between the light's direction
// of travel and the direction towards the eye (ref_phase_hg).
float medium_phase(float cos_theta)
{
    float g = u_medium_g;
    float denom = max(1.0 + g * g - 2.0 * g * cos_theta, 1e-12);
    return (1.0 - g * g) / (4.0 * PI * denom * sqrt(denom));
}
