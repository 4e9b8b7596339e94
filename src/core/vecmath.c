#include "core/vecmath.h"

#include <math.h>

float math_safe_div(float a, float b, float fallback)
{
    if (!(fabsf(b) > 1e-30f))
        return fallback;
    float r = a / b;
    return isfinite(r) ? r : fallback;
}

double math_safe_div_d(double a, double b, double fallback)
{
    if (!(fabs(b) > 1e-300))
        return fallback;
    double r = a / b;
    return isfinite(r) ? r : fallback;
}

bool math_finite3(vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

vec3 vec3_make(float x, float y, float z) { return (vec3){x, y, z}; }
vec3 vec3_add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
vec3 vec3_sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
vec3 vec3_lerp(vec3 a, vec3 b, float t) { return (vec3){a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t}; }
vec3 vec3_scale(vec3 a, float s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
vec3 vec3_mul(vec3 a, vec3 b) { return (vec3){a.x * b.x, a.y * b.y, a.z * b.z}; }
float vec3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float vec3_length(vec3 a) { return sqrtf(vec3_dot(a, a)); }
vec3 vec3_normalize_or(vec3 a, vec3 fallback)
{
    float len = vec3_length(a);
    if (!(len > 1e-20f) || !isfinite(len))
        return fallback;
    return vec3_scale(a, 1.0f / len);
}
vec3 vec3_min(vec3 a, vec3 b) { return (vec3){fminf(a.x, b.x), fminf(a.y, b.y), fminf(a.z, b.z)}; }
vec3 vec3_max(vec3 a, vec3 b) { return (vec3){fmaxf(a.x, b.x), fmaxf(a.y, b.y), fmaxf(a.z, b.z)}; }

mat4 mat4_identity(void)
{
    mat4 r = {{0}};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
    return r;
}

mat4 mat4_mul(mat4 a, mat4 b)
{
    mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++)
                s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

vec3 mat4_transform_point(mat4 m, vec3 p)
{
    float x = m.m[0] * p.x + m.m[4] * p.y + m.m[8] * p.z + m.m[12];
    float y = m.m[1] * p.x + m.m[5] * p.y + m.m[9] * p.z + m.m[13];
    float z = m.m[2] * p.x + m.m[6] * p.y + m.m[10] * p.z + m.m[14];
    float w = m.m[3] * p.x + m.m[7] * p.y + m.m[11] * p.z + m.m[15];
    float inv = math_safe_div(1.0f, w, 1.0f);
    return (vec3){x * inv, y * inv, z * inv};
}

vec3 mat4_transform_dir(mat4 m, vec3 d)
{
    return (vec3){m.m[0] * d.x + m.m[4] * d.y + m.m[8] * d.z,
                  m.m[1] * d.x + m.m[5] * d.y + m.m[9] * d.z,
                  m.m[2] * d.x + m.m[6] * d.y + m.m[10] * d.z};
}

mat4 mat4_translate(vec3 t)
{
    mat4 r = mat4_identity();
    r.m[12] = t.x;
    r.m[13] = t.y;
    r.m[14] = t.z;
    return r;
}

mat4 mat4_scale(vec3 s)
{
    mat4 r = mat4_identity();
    r.m[0] = s.x;
    r.m[5] = s.y;
    r.m[10] = s.z;
    return r;
}

mat4 mat4_from_quat(quat q)
{
    q = quat_normalize(q);
    float x = q.x, y = q.y, z = q.z, w = q.w;
    mat4 r = mat4_identity();
    r.m[0] = 1 - 2 * (y * y + z * z);
    r.m[1] = 2 * (x * y + z * w);
    r.m[2] = 2 * (x * z - y * w);
    r.m[4] = 2 * (x * y - z * w);
    r.m[5] = 1 - 2 * (x * x + z * z);
    r.m[6] = 2 * (y * z + x * w);
    r.m[8] = 2 * (x * z + y * w);
    r.m[9] = 2 * (y * z - x * w);
    r.m[10] = 1 - 2 * (x * x + y * y);
    return r;
}

mat4 mat4_trs(vec3 t, quat r, vec3 s)
{
    return mat4_mul(mat4_translate(t), mat4_mul(mat4_from_quat(r), mat4_scale(s)));
}

mat4 mat4_perspective(float fovy_deg, float aspect, float znear, float zfar)
{
    float f = math_safe_div(1.0f, tanf(fovy_deg * (float)MATH_PI / 360.0f), 1.0f);
    mat4 r = {{0}};
    r.m[0] = math_safe_div(f, aspect, f);
    r.m[5] = f;
    r.m[10] = math_safe_div(zfar + znear, znear - zfar, -1.0f);
    r.m[11] = -1.0f;
    r.m[14] = math_safe_div(2.0f * zfar * znear, znear - zfar, -2.0f * znear);
    return r;
}

mat4 mat4_ortho(float l, float r, float b, float t, float n, float f)
{
    mat4 m = mat4_identity();
    m.m[0] = math_safe_div(2.0f, r - l, 1.0f);
    m.m[5] = math_safe_div(2.0f, t - b, 1.0f);
    m.m[10] = math_safe_div(-2.0f, f - n, -1.0f);
    m.m[12] = math_safe_div(-(r + l), r - l, 0.0f);
    m.m[13] = math_safe_div(-(t + b), t - b, 0.0f);
    m.m[14] = math_safe_div(-(f + n), f - n, 0.0f);
    return m;
}

mat4 mat4_cube_face_view(vec3 eye, int face)
{
    static const float dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const float ups[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    int f = face < 0 ? 0 : face > 5 ? 5 : face;
    return mat4_look_at(eye, vec3_add(eye, vec3_make(dirs[f][0], dirs[f][1], dirs[f][2])),
                        vec3_make(ups[f][0], ups[f][1], ups[f][2]));
}

mat4 mat4_look_at(vec3 eye, vec3 target, vec3 up)
{
    vec3 f = vec3_normalize_or(vec3_sub(target, eye), vec3_make(0, 0, -1));
    if (fabsf(vec3_dot(f, vec3_normalize_or(up, vec3_make(0, 1, 0)))) > 0.999f)
        up = fabsf(f.y) < 0.9f ? vec3_make(0, 1, 0) : vec3_make(1, 0, 0);
    vec3 s = vec3_normalize_or(vec3_cross(f, up), vec3_make(1, 0, 0));
    vec3 u = vec3_cross(s, f);
    mat4 r = mat4_identity();
    r.m[0] = s.x;
    r.m[4] = s.y;
    r.m[8] = s.z;
    r.m[1] = u.x;
    r.m[5] = u.y;
    r.m[9] = u.z;
    r.m[2] = -f.x;
    r.m[6] = -f.y;
    r.m[10] = -f.z;
    r.m[12] = -vec3_dot(s, eye);
    r.m[13] = -vec3_dot(u, eye);
    r.m[14] = vec3_dot(f, eye);
    return r;
}

mat4 mat4_transpose(mat4 m)
{
    mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++)
            r.m[c * 4 + row] = m.m[row * 4 + c];
    return r;
}

bool mat4_inverse(mat4 mat, mat4 *out)
{
    /* Cofactor expansion (as in MESA's gluInvertMatrix), in double. */
    double m[16], inv[16];
    for (int i = 0; i < 16; i++)
        m[i] = mat.m[i];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabs(det) > 1e-30) || !isfinite(det)) {
        *out = mat4_identity();
        return false;
    }
    for (int i = 0; i < 16; i++)
        out->m[i] = (float)(inv[i] / det);
    return true;
}

quat quat_identity(void) { return (quat){0, 0, 0, 1}; }

quat quat_axis_angle(vec3 axis, float radians)
{
    vec3 a = vec3_normalize_or(axis, vec3_make(0, 1, 0));
    float s = sinf(radians * 0.5f);
    return (quat){a.x * s, a.y * s, a.z * s, cosf(radians * 0.5f)};
}

quat quat_mul(quat a, quat b)
{
    return (quat){a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                  a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                  a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
                  a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

quat quat_normalize(quat q)
{
    float len = sqrtf(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (!(len > 1e-20f) || !isfinite(len))
        return quat_identity();
    return (quat){q.x / len, q.y / len, q.z / len, q.w / len};
}
