#version 450 core
// Volumetric light with shadows (Liktor & Dachsbacher 2011, §7 "Volumetric
// Lighting" and Fig. 8 B): single scattering of the lights' direct light
// along each camera ray through the scene's medium, shadowed by the shadow
// maps and attenuated on the way in (medium_transmittance) and out; the
// surface behind is attenuated by the medium between it and the eye, and
// the images in `add` (volume caustics, already attenuated) are summed on
// top. One jittered sample per step (interleaved gradient noise), as the
// reference takes one uniformly placed sample per segment and iteration.
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
uniform sampler2D u_color;
uniform sampler2D u_depth;
uniform sampler2D u_add[4];
// The pass's values (issue 54: one block, mirrored by struct volume_light_params)
layout(std140) uniform VolumeLightParams {
    int u_add_count; // images added to the result (`add`)
    int u_steps;     // samples along each view ray
};
out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 color = texelFetch(u_color, px, 0);
    float depth = texelFetch(u_depth, px, 0).r;
    vec2 ndc = gl_FragCoord.xy * u_viewport.zw * 2.0 - 1.0;
    vec4 a = u_inv_view_proj * vec4(ndc, -1.0, 1.0), b = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w, dir = normalize(b.xyz / b.w - o);
    if (!camera_is_ortho())
        o = u_camera_pos.xyz; // the medium around the eye absorbs from there (as the reference)
    float tmax = 1e30;
    if (depth < 1.0) {
        vec4 s = u_inv_view_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
        tmax = max(dot(s.xyz / s.w - o, dir), 0.0);
    }
    vec3 inscatter = vec3(0.0), transmittance = vec3(1.0);
    float t0, t1;
    if (medium_clip(o, dir, tmax, t0, t1)) {
        int steps = max(u_steps, 1);
        float dt = (t1 - t0) / float(steps);
        float jitter = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
        vec3 tau = vec3(0.0); // optical depth from the eye to the step's start
        for (int i = 0; i < steps; i++) {
            float t = t0 + (float(i) + jitter) * dt;
            vec3 x = o + dir * t;
            float rho = medium_density(x);
            vec3 step_tau = u_medium_sigma_t * (rho * dt);
            if (rho > 0.0) {
                vec3 to_eye = exp(-(tau + step_tau * jitter));
                vec3 sum = vec3(0.0);
                for (int l = 0; l < u_counts.x; l++) {
                    vec3 to_light;
                    float dist;
                    vec3 e = light_arrival(l, x, to_light, dist);
                    if (max(e.r, max(e.g, e.b)) <= 0.0)
                        continue;
                    e *= visibility(l, x, to_light, to_light);
                    if (max(e.r, max(e.g, e.b)) <= 0.0)
                        continue;
                    sum += e * medium_transmittance_ray(x, to_light, dist) * medium_phase(dot(to_light, dir));
                }
                inscatter += to_eye * u_medium_sigma_s * (rho * dt) * sum;
            }
            tau += step_tau;
        }
        transmittance = u_medium_grid == 1 ? exp(-tau) : medium_transmittance_ray(o, dir, tmax);
    }
    vec3 added = vec3(0.0);
    for (int k = 0; k < u_add_count; k++)
        added += texelFetch(u_add[k], px, 0).rgb;
    o_color = vec4(color.rgb * transmittance + inscatter + added, color.a);
}
