// Approximate ray tracing against the receivers with a distance impostor
// (Szirmay-Kalos et al. 2005, the exits of Liktor & Dachsbacher 2011 §4.3
// and §6): a cube map around the refractors' centre holding, per
// direction, the distance to the nearest diffuse surface. A ray is
// marched until it passes the stored distance, then bisected.
uniform samplerCube u_distance;  // distance_map_update_distances: the range where no receiver is within it
// (u_distance_center and u_distance_range: BeamParams, beams.glsl)
const int DISTANCE_STEPS = 48;

// Is p beyond the receivers in its direction from the centre?
bool distance_beyond(vec3 p)
{
    vec3 v = p - u_distance_center;
    float stored = texture(u_distance, v).r;
    if (stored >= 0.999 * u_distance_range)
        return false; // no receiver in this direction (the cleared value)
    return dot(v, v) >= stored * stored;
}

// The distance along o + t d (d unit) to the first receiver, or the range
// when the ray meets none.
float distance_trace(vec3 o, vec3 d)
{
    float step = u_distance_range / float(DISTANCE_STEPS), lo = 0.0;
    if (distance_beyond(o))
        return 0.0;
    for (int j = 1; j <= DISTANCE_STEPS; j++) {
        float t = step * float(j);
        if (distance_beyond(o + d * t)) {
            float hi = t;
            for (int i = 0; i < 8; i++) {
                float m = 0.5 * (lo + hi);
                if (distance_beyond(o + d * m))
                    hi = m;
                else
                    lo = m;
            }
            return hi;
        }
        lo = t;
    }
    return u_distance_range;
}

// How far a beam's edge ray needs to be extruded: to the first receiver,
// or, meeting none, to where it leaves the medium (nothing scatters past
// it), or nowhere when it never enters one.
float extrusion_length(vec3 o, vec3 d)
{
    float len = distance_trace(o, d);
    if (len < u_distance_range)
        return len;
    float t0, t1;
    return medium_clip(o, d, len, t0, t1) ? t1 : 0.0;
}
