#version 450 core
// Sandberg & Falemo §3.2: per water triangle, the refracted rays R_i at its
// vertices and the six corners of its caustic volume; §3.4: the light
// power I0 entering through the triangle (irradiance x cos(theta_i) x
// Fresnel transmittance x area). A light below the horizon, a zero-area
// triangle or a ray that does not go down gives an empty volume.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "common/shadows.glsl"
#include "caustic_volumes/volume.glsl"
layout(local_size_x = 64) in;
layout(std430) readonly buffer Positions { float positions[]; };
layout(std430) readonly buffer Normals { float normals[]; };
// (its values: CausticVolumesParams, volume.glsl)

vec3 fetch(int v, bool normal)
{
    int i = v * 3;
    return normal ? vec3(normals[i], normals[i + 1], normals[i + 2])
                  : vec3(positions[i], positions[i + 1], positions[i + 2]);
}

// The surface at generator vertex (i, j): bilinear in the water's grid.
vec3 surface(int i, int j, bool normal)
{
    vec2 s = vec2(u_water_resolution - 1) / vec2(u_resolution - 1);
    vec2 f = vec2(float(i), float(j)) * s;
    ivec2 a = min(ivec2(floor(f)), u_water_resolution - 2);
    vec2 t = f - vec2(a);
    int n = u_water_resolution.x;
    vec3 v00 = fetch(a.y * n + a.x, normal), v10 = fetch(a.y * n + a.x + 1, normal);
    vec3 v01 = fetch((a.y + 1) * n + a.x, normal), v11 = fetch((a.y + 1) * n + a.x + 1, normal);
    return mix(mix(v00, v10, t.x), mix(v01, v11, t.x), t.y);
}

void empty_volume(uint id)
{
    for (int k = 0; k < 3; k++) {
        volumes[id].top[k] = vec4(0.0);
        volumes[id].dir[k] = vec4(0.0, -1.0, 0.0, 0.0);
        volumes[id].bottom[k] = vec4(0.0);
    }
    volumes[id].flux = vec4(0.0);
}

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (id >= uint(u_triangles))
        return;
    GpuLight light = u_lights[u_light];
    bool directional = int(light.position.w + 0.5) == 1;
    // triangle id of the generator grid, counter-clockwise seen from above
    // (as mesh_create_grid winds them): (a, b, a+1) and (a+1, b, b+1)
    int cells = u_resolution.x - 1;
    int cell = int(id) / 2, ci = cell % cells, cj = cell / cells;
    ivec2 corner[3] = (int(id) % 2 == 0) ? ivec2[3](ivec2(ci, cj), ivec2(ci, cj + 1), ivec2(ci + 1, cj))
                                         : ivec2[3](ivec2(ci + 1, cj), ivec2(ci, cj + 1), ivec2(ci + 1, cj + 1));
    vec3 p[3], r[3];
    for (int k = 0; k < 3; k++) {
        p[k] = (u_model * vec4(surface(corner[k].x, corner[k].y, false), 1.0)).xyz;
        vec3 n = normalize(mat3(u_normal_matrix) * surface(corner[k].x, corner[k].y, true));
        vec3 l = directional ? normalize(light.direction.xyz) : normalize(p[k] - light.position.xyz);
        if (dot(n, l) >= 0.0) { // lit from below the surface: no light enters here
            empty_volume(id);
            return;
        }
        r[k] = refract(l, n, 1.0 / u_ior); // air to water: no total internal reflection
        if (dot(r[k], r[k]) == 0.0 || r[k].y > -1e-3) {
            empty_volume(id);
            return;
        }
        r[k] = normalize(r[k]);
    }
    vec3 cr = cross(p[1] - p[0], p[2] - p[0]);
    float area = 0.5 * length(cr);
    vec3 centre = (p[0] + p[1] + p[2]) / 3.0;
    vec3 l = directional ? normalize(light.direction.xyz) : normalize(centre - light.position.xyz);
    vec3 face = area > 1e-12 ? cr / (2.0 * area) : vec3(0.0, 1.0, 0.0);
    if (face.y < 0.0)
        face = -face;
    float cos_i = -dot(l, face);
    if (area <= 1e-12 || cos_i <= 0.0) {
        empty_volume(id);
        return;
    }
    vec3 e = light.intensity.rgb;
    if (!directional) {
        vec3 d = centre - light.position.xyz;
        e /= max(dot(d, d), 1e-8);
    }
    float transmit = 1.0 - fresnel_of(cos_i, 1.0 / u_ior, u_ideal);
    // the panes between the light and the water let (1 - F) x tint of it
    // through, from the light's shadow map where the pass reads one (its
    // pane filter at the triangle's centre), as the reference's photons
    // cross them (issue 50)
    e *= pane_filter(u_light, centre, face, -l);
    for (int k = 0; k < 3; k++) {
        float t = (u_bottom - p[k].y) / r[k].y;
        volumes[id].top[k] = vec4(p[k], 1.0);
        volumes[id].dir[k] = vec4(r[k], 0.0);
        volumes[id].bottom[k] = vec4(p[k] + max(t, 0.0) * r[k], 1.0);
    }
    volumes[id].flux = vec4(e * cos_i * transmit * area, area);
}
