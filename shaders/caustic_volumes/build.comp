#version 450 core
// Sandberg & Falemo §3.2: per water triangle, the refracted rays R_i at its
// vertices and the six corners of its caustic volume; §3.4: the light
// power I0 entering through the triangle (irradiance x cos(theta_i) x
// Fresnel transmittance x area). A light below the horizon, a zero-area
// triangle or a ray that does not go down gives an empty volume.
#include "common/frame.glsl"
#include "common/fresnel.glsl"
#include "caustic_volumes/volume.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) readonly buffer Normals { float normals[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
uniform int u_triangles;
uniform int u_light;
uniform float u_ior;
uniform float u_bottom;

vec3 fetch(uint v, bool normal)
{
    uint i = v * 3u;
    return normal ? vec3(normals[i], normals[i + 1u], normals[i + 2u])
                  : vec3(positions[i], positions[i + 1u], positions[i + 2u]);
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
    vec3 p[3], r[3];
    for (int k = 0; k < 3; k++) {
        uint v = indices[id * 3u + uint(k)];
        p[k] = (u_model * vec4(fetch(v, false), 1.0)).xyz;
        vec3 n = normalize(mat3(u_normal_matrix) * fetch(v, true));
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
    float transmit = 1.0 - fresnel_dielectric(cos_i, 1.0 / u_ior);
    for (int k = 0; k < 3; k++) {
        float t = (u_bottom - p[k].y) / r[k].y;
        volumes[id].top[k] = vec4(p[k], 1.0);
        volumes[id].dir[k] = vec4(r[k], 0.0);
        volumes[id].bottom[k] = vec4(p[k] + max(t, 0.0) * r[k], 1.0);
    }
    volumes[id].flux = vec4(e * cos_i * transmit * area, area);
}
