/* Small linear algebra for the CPU side: vec3, column-major mat4 (as GLSL
 * expects), unit quaternions. Every division by a length goes through a
 * guarded helper (CONVENTIONS.md: no bare `/` by a length or cosine). */
#ifndef CAUSTICA_VECMATH_H
#define CAUSTICA_VECMATH_H

#include <stdbool.h>

typedef struct { float x, y, z; } vec3;
typedef struct { float x, y, z, w; } quat;
typedef struct { float m[16]; } mat4; /* column-major: m[col * 4 + row] */

#define MATH_PI 3.14159265358979323846

/* a / b, or `fallback` when |b| is too small or the result is not finite. */
float math_safe_div(float a, float b, float fallback);
double math_safe_div_d(double a, double b, double fallback);
bool math_finite3(vec3 v);

vec3 vec3_make(float x, float y, float z);
vec3 vec3_add(vec3 a, vec3 b);
vec3 vec3_sub(vec3 a, vec3 b);
vec3 vec3_scale(vec3 a, float s);
vec3 vec3_mul(vec3 a, vec3 b);
float vec3_dot(vec3 a, vec3 b);
vec3 vec3_cross(vec3 a, vec3 b);
float vec3_length(vec3 a);
/* Unit vector along `a`, or `fallback` when `a` has (near) zero length. */
vec3 vec3_normalize_or(vec3 a, vec3 fallback);
vec3 vec3_min(vec3 a, vec3 b);
/* a + (b - a) t */
vec3 vec3_lerp(vec3 a, vec3 b, float t);
vec3 vec3_max(vec3 a, vec3 b);

mat4 mat4_identity(void);
mat4 mat4_mul(mat4 a, mat4 b);
vec3 mat4_transform_point(mat4 m, vec3 p);
vec3 mat4_transform_dir(mat4 m, vec3 d);
mat4 mat4_translate(vec3 t);
mat4 mat4_scale(vec3 s);
mat4 mat4_from_quat(quat q);
/* Translation * rotation * scale, the order glTF and the scene API use. */
mat4 mat4_trs(vec3 t, quat r, vec3 s);
mat4 mat4_perspective(float fovy_deg, float aspect, float znear, float zfar);
mat4 mat4_ortho(float l, float r, float b, float t, float n, float f);
/* View matrix looking from eye at target; `up` is replaced when parallel
 * to the viewing direction so the matrix never degenerates. */
mat4 mat4_look_at(vec3 eye, vec3 target, vec3 up);
/* The view from `eye` through cube-map face `face` (0..5: +X -X +Y -Y +Z -Z,
 * OpenGL's order) with that face's up vector: with a 90-degree square
 * perspective, what the face of a cube map centred at `eye` holds. */
mat4 mat4_cube_face_view(vec3 eye, int face);
/* General inverse; returns identity (and false) for a singular matrix. */
bool mat4_inverse(mat4 m, mat4 *out);
mat4 mat4_transpose(mat4 m);

quat quat_identity(void);
quat quat_axis_angle(vec3 axis, float radians);
quat quat_mul(quat a, quat b);
quat quat_normalize(quat q);

#endif
