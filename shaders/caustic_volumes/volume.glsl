// One caustic volume (std430): the generator triangle's corners, the unit
// refracted light rays at them, the rays' ends below the deepest receiver,
// and the light power through the triangle (rgb) with its area (w).
struct CausticVolume {
    vec4 top[3];
    vec4 dir[3];
    vec4 bottom[3];
    vec4 flux;
};
layout(std430) buffer Volumes { CausticVolume volumes[]; };

// The pass's values for one frame, both passes' (issue 54): one block,
// uploaded in one call, mirrored by struct caustic_volumes_params in
// src/passes/techniques/caustic_volumes.c (gl_param_block).
layout(std140) uniform CausticVolumesParams {
    mat4 u_model;             // the water surface's (its simulated vertices are in object space)
    mat4 u_normal_matrix;
    vec3 u_attenuation;       // the water's absorption per unit length (Beer-Lambert along the volume)
    float u_ior;              // the water's
    ivec2 u_water_resolution; // the simulation's vertices along x and z
    ivec2 u_resolution;       // the generator grid's
    int u_triangles;          // generator triangles (one volume each)
    int u_light;              // the light's entry in the frame's list
    float u_ideal;            // 1: the water refracts all the light (no Fresnel)
    float u_bottom;           // where the volumes end: just below the deepest receiver (§3.5)
    float u_cap;              // the bound on a volume's irradiance gain (a focus)
};
