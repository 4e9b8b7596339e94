// Exact unpolarised Fresnel reflectance for a dielectric interface.
// eta = n_incident / n_transmitted; cos_i = cosine of the incident angle.
// Returns 1 under total internal reflection; never NaN (the square root's
// argument is clamped, and IOR 1.0 gives exactly 0).
float fresnel_dielectric(float cos_i, float eta)
{
    cos_i = clamp(cos_i, 0.0, 1.0);
    float sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0)
        return 1.0;
    float cos_t = sqrt(max(0.0, 1.0 - sin2_t));
    float rs = (eta * cos_i - cos_t) / max(eta * cos_i + cos_t, 1e-8);
    float rp = (cos_i - eta * cos_t) / max(cos_i + eta * cos_t, 1e-8);
    return clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

// The reflectance of a material's interface: Fresnel's, or for an ideal
// one (`fresnel = false`, ideal > 0.5) none at all unless refraction is
// impossible, where it is total. The reference's choice is the same
// (src/reference/ref_sppm.c, fresnel_of).
float fresnel_of(float cos_i, float eta, float ideal)
{
    if (ideal < 0.5)
        return fresnel_dielectric(cos_i, eta);
    cos_i = clamp(cos_i, 0.0, 1.0);
    return eta * eta * (1.0 - cos_i * cos_i) >= 1.0 ? 1.0 : 0.0;
}

// A light-space G-buffer carries a dielectric's IOR in one float; an ideal
// interface adds IDEAL_IOR_OFFSET to it (IORs are far below it).
const float IDEAL_IOR_OFFSET = 64.0;

// Refraction of unit `v` about unit normal `n` (facing against v); falls
// back to reflection under total internal reflection instead of returning 0.
vec3 refract_or_reflect(vec3 v, vec3 n, float eta)
{
    vec3 t = refract(v, n, eta);
    return dot(t, t) > 0.0 ? normalize(t) : reflect(v, n);
}
