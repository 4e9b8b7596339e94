#version 450 core
// Morph targets, a glTF skin (SKINNED 1), then a deformer, per vertex,
// into the object's frame buffers. DEFORM_KIND: 0 morphs only, 1 wave, 2 a
// GLSL function from the script, `vec3 deform(vec3 p, float t)`, inserted
// above this line.
layout(local_size_x = 256) in;

layout(std430) readonly buffer BasePositions { float base_positions[]; };
layout(std430) readonly buffer BaseNormals { float base_normals[]; };
layout(std430) readonly buffer TargetPositions { float target_positions[]; };
layout(std430) readonly buffer TargetNormals { float target_normals[]; };
layout(std430) writeonly buffer OutPositions { float out_positions[]; };
layout(std430) writeonly buffer OutNormals { float out_normals[]; };

#if SKINNED
// glTF 2.0 §3.7.3: four joints a vertex (their indices as floats), their
// weights (summing to 1, or all 0: not skinned), and each joint's world
// matrix times its inverse bind matrix, this frame
layout(std430) readonly buffer Joints { float joints[]; };
layout(std430) readonly buffer JointWeights { float joint_weights[]; };
layout(std430) readonly buffer JointMatrices { mat4 joint_matrices[]; };
uniform int u_joint_count;
#endif

uniform int u_vertex_count;
uniform int u_target_count;
uniform float u_weights[8];
uniform float u_time;
uniform vec4 u_wave;           // amplitude, frequency, speed
uniform vec3 u_wave_direction; // direction the wave travels in xz
uniform float u_step;          // finite-difference step for normals


vec3 apply_deform(vec3 p)
{
#if DEFORM_KIND == 1
    float phase = u_wave.y * dot(p, u_wave_direction) - u_wave.z * u_time;
    return p + vec3(0.0, u_wave.x * sin(phase), 0.0);
#elif DEFORM_KIND == 2
    return deform(p, u_time);
#else
    return p;
#endif
}

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= uint(u_vertex_count))
        return;
    uint i = v * 3u;
    vec3 p = vec3(base_positions[i], base_positions[i + 1u], base_positions[i + 2u]);
    vec3 n = vec3(base_normals[i], base_normals[i + 1u], base_normals[i + 2u]);
    uint stride = uint(u_vertex_count) * 3u;
    for (int t = 0; t < u_target_count; t++) {
        uint j = uint(t) * stride + i;
        p += u_weights[t] * vec3(target_positions[j], target_positions[j + 1u], target_positions[j + 2u]);
        n += u_weights[t] * vec3(target_normals[j], target_normals[j + 1u], target_normals[j + 2u]);
    }
#if SKINNED
    // the skin after the morphs (glTF 2.0 §3.7.3.3): the weighted blend of
    // the joints' matrices; the normal by its cofactor (a blend of
    // rotations and scales need not be orthogonal)
    uint k4 = v * 4u;
    vec4 w = vec4(joint_weights[k4], joint_weights[k4 + 1u], joint_weights[k4 + 2u], joint_weights[k4 + 3u]);
    if (w.x + w.y + w.z + w.w > 0.0) {
        mat4 s = mat4(0.0);
        for (uint k = 0u; k < 4u; k++) {
            int j = int(joints[k4 + k]);
            if (w[k] > 0.0 && j >= 0 && j < u_joint_count)
                s += w[k] * joint_matrices[j];
        }
        p = (s * vec4(p, 1.0)).xyz;
        mat3 m = mat3(s);
        n = mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1])) * n;
    }
#endif
    vec3 q = apply_deform(p);
#if DEFORM_KIND != 0
    // Normals transform by the cofactor of the deformation's Jacobian,
    // estimated by forward differences: n' = n.x (j1 x j2) + n.y (j2 x j0) + n.z (j0 x j1).
    float h = u_step;
    vec3 j0 = (apply_deform(p + vec3(h, 0, 0)) - q) / h;
    vec3 j1 = (apply_deform(p + vec3(0, h, 0)) - q) / h;
    vec3 j2 = (apply_deform(p + vec3(0, 0, h)) - q) / h;
    n = n.x * cross(j1, j2) + n.y * cross(j2, j0) + n.z * cross(j0, j1);
#endif
    // Blended normals are renormalised; a degenerate one falls back to +Y.
    float len = length(n);
    n = (len > 1e-12 && !isnan(len) && !isinf(len)) ? n / len : vec3(0.0, 1.0, 0.0);
    if (any(isnan(q)) || any(isinf(q)))
        q = p;
    out_positions[i] = q.x; out_positions[i + 1u] = q.y; out_positions[i + 2u] = q.z;
    out_normals[i] = n.x; out_normals[i + 1u] = n.y; out_normals[i + 2u] = n.z;
}
