/* The glTF 2.0 BRDF on the CPU (core/brdf.h); the GPU's is
 * shaders/common/brdf.glsl, line for line. */
#include "core/brdf.h"

#include <math.h>
#include <pthread.h>

#include "core/vecmath.h"

struct brdf_material brdf_material_default(double r, double g, double b, double metallic, double roughness)
{
    return (struct brdf_material){.base_color = {r, g, b},
                                  .metallic = metallic,
                                  .roughness = roughness,
                                  .ior = 1.5,
                                  .specular = 1.0,
                                  .specular_color = {1.0, 1.0, 1.0},
                                  .clearcoat = 0.0,
                                  .clearcoat_roughness = 0.0,
                                  .clearcoat_normal = {0.0, 0.0, 1.0}};
}

static void ambient_terms(double n_dot_v, double roughness, double out[3]);

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double brdf_ggx_d(double n_dot_h, double sin2, double alpha)
{
    /* Appendix B: D = alpha^2 / (pi ((NdotH)^2 (alpha^2 - 1) + 1)^2),
     * the denominator as NdotH^2 alpha^2 + sin^2 */
    double a2 = alpha * alpha;
    double k = n_dot_h * n_dot_h * a2 + fmax(sin2, 0.0);
    return n_dot_h > 0.0 ? a2 / (MATH_PI * k * k) : 0.0;
}

double brdf_smith_v(double n_dot_l, double n_dot_v, double alpha)
{
    /* Appendix B: V = 0.5 / (NdotL sqrt(NdotV^2 (1 - a^2) + a^2) + NdotV sqrt(NdotL^2 (1 - a^2) + a^2)) */
    double a2 = alpha * alpha;
    double gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    double gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    double s = gv + gl;
    return s > 0.0 ? 0.5 / s : 0.0;
}

void brdf_gltf(const double n[3], const double v[3], const double l[3], const struct brdf_material *m, double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double n_dot_l = dot3(n, l), n_dot_v = dot3(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return;
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double hl = sqrt(dot3(h, h));
    if (!(hl > 1e-12))
        return; /* v = -l: both above the surface cannot give this, but no division by 0 */
    for (int k = 0; k < 3; k++)
        h[k] /= hl;
    double n_dot_h = fmin(dot3(n, h), 1.0), v_dot_h = fmin(fabs(dot3(v, h)), 1.0);
    double alpha = fmax(m->roughness * m->roughness, BRDF_MIN_ALPHA);
    double c[3] = {n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]};
    double spec = brdf_ggx_d(n_dot_h, dot3(c, c), alpha) * brdf_smith_v(n_dot_l, n_dot_v, alpha);
    double w = pow(1.0 - v_dot_h, 5.0);
    double r0 = (m->ior - 1.0) / (m->ior + 1.0);
    double fd[3], f0_max = 0.0;
    for (int k = 0; k < 3; k++) {
        double f0 = fmin(r0 * r0 * m->specular_color[k], 1.0);
        fd[k] = f0 + (1.0 - f0) * w;
        f0_max = fmax(f0_max, f0);
    }
    double diffuse_weight = 1.0 - m->specular * brdf_specular_albedo(n_dot_v, m->roughness, f0_max);
    for (int k = 0; k < 3; k++) {
        double dielectric = diffuse_weight * m->base_color[k] / MATH_PI + m->specular * fd[k] * spec;
        double metal = (m->base_color[k] + (1.0 - m->base_color[k]) * w) * spec;
        f[k] = dielectric + m->metallic * (metal - dielectric);
    }
}

double brdf_clearcoat_share(const double v[3], const struct brdf_material *m)
{
    if (!(m->clearcoat > 0.0))
        return 0.0;
    /* KHR_materials_clearcoat's fresnel_coat: f0 of IOR 1.5, |n_c . v| */
    double c = fmin(fabs(dot3(m->clearcoat_normal, v)), 1.0);
    return m->clearcoat * (0.04 + 0.96 * pow(1.0 - c, 5.0));
}

/* The coat's lobe D_c V_c (n_c . l), 0 below n_c */
static double clearcoat_lobe_cos(const double v[3], const double l[3], const struct brdf_material *m)
{
    const double *n = m->clearcoat_normal;
    double n_dot_l = dot3(n, l), n_dot_v = dot3(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return 0.0;
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double hl = sqrt(dot3(h, h));
    if (!(hl > 1e-12))
        return 0.0;
    for (int k = 0; k < 3; k++)
        h[k] /= hl;
    double alpha = fmax(m->clearcoat_roughness * m->clearcoat_roughness, BRDF_MIN_ALPHA);
    double c[3] = {n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]};
    return brdf_ggx_d(fmin(dot3(n, h), 1.0), dot3(c, c), alpha) * brdf_smith_v(n_dot_l, n_dot_v, alpha) * n_dot_l;
}

void brdf_gltf_cos(const double n[3], const double v[3], const double l[3], const struct brdf_material *m,
                   double out[3])
{
    brdf_gltf(n, v, l, m, out);
    double c = fmax(dot3(n, l), 0.0);
    double share = brdf_clearcoat_share(v, m);
    double coat = share > 0.0 ? share * clearcoat_lobe_cos(v, l, m) : 0.0;
    for (int k = 0; k < 3; k++)
        out[k] = (1.0 - share) * out[k] * c + coat;
}

void brdf_gltf_specular_cos(const double n[3], const double v[3], const double l[3], const struct brdf_material *m,
                            double out[3])
{
    brdf_gltf_cos(n, v, l, m, out);
    double n_dot_l = dot3(n, l), n_dot_v = dot3(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return; /* (the diffuse lobe is 0 there too) */
    double diffuse[3];
    brdf_diffuse_albedo(n, v, m, diffuse); /* (1 - share) (1 - metallic) c (1 - s E) */
    for (int k = 0; k < 3; k++)
        out[k] = fmax(out[k] - diffuse[k] / MATH_PI * n_dot_l, 0.0);
}

/* Smith's G1 for GGX at cosine c (the masking of one direction) */
static double smith_g1(double c, double alpha)
{
    double a2 = alpha * alpha;
    return 2.0 * c / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

/* The density of l (solid angle) when h is drawn from GGX's visible
 * normals about unit n for view v and l = reflect(-v, h): G1(v) D(h) /
 * (4 n . v) (Heitz 2018, eq. 17 over the reflection's Jacobian); 0 where v
 * is below n */
static double vndf_pdf_l(const double n[3], const double v[3], const double l[3], double alpha)
{
    double n_dot_v = dot3(n, v);
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double hl = sqrt(dot3(h, h));
    if (!(n_dot_v > 0.0) || !(hl > 1e-12))
        return 0.0;
    for (int k = 0; k < 3; k++)
        h[k] /= hl;
    double n_dot_h = fmin(dot3(n, h), 1.0);
    double c[3] = {n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]};
    return smith_g1(fmin(n_dot_v, 1.0), alpha) * brdf_ggx_d(n_dot_h, dot3(c, c), alpha) / (4.0 * n_dot_v);
}

/* A unit frame t, b about unit axis */
static void frame_about(const double axis[3], double t[3], double b[3])
{
    if (fabs(axis[0]) > 0.9)
        t[0] = 0.0, t[1] = 1.0, t[2] = 0.0;
    else
        t[0] = 1.0, t[1] = 0.0, t[2] = 0.0;
    double d = dot3(t, axis);
    for (int k = 0; k < 3; k++)
        t[k] -= d * axis[k];
    double tl = sqrt(dot3(t, t));
    for (int k = 0; k < 3; k++)
        t[k] /= tl;
    b[0] = axis[1] * t[2] - axis[2] * t[1], b[1] = axis[2] * t[0] - axis[0] * t[2], b[2] = axis[0] * t[1] - axis[1] * t[0];
}

bool brdf_sample_specular(const double n[3], const double v[3], const struct brdf_material *m, double u1, double u2,
                          double u3, double l[3], double *pdf)
{
    bool coat = m->clearcoat > 0.0;
    bool pick_coat = coat && u3 < 0.5;
    const double *axis = pick_coat ? m->clearcoat_normal : n;
    double rough = pick_coat ? m->clearcoat_roughness : m->roughness;
    double alpha = fmax(rough * rough, BRDF_MIN_ALPHA);
    double t[3], b[3];
    frame_about(axis, t, b);
    double vl[3] = {dot3(v, t), dot3(v, b), dot3(v, axis)}; /* v in the lobe's frame */
    if (!(vl[2] > 0.0))
        return false;
    /* Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1 */
    double vh[3] = {alpha * vl[0], alpha * vl[1], vl[2]};
    double vhl = sqrt(dot3(vh, vh));
    for (int k = 0; k < 3; k++)
        vh[k] /= vhl;
    double lensq = vh[0] * vh[0] + vh[1] * vh[1];
    double t1v[3] = {1.0, 0.0, 0.0};
    if (lensq > 1e-24) {
        double inv = 1.0 / sqrt(lensq);
        t1v[0] = -vh[1] * inv, t1v[1] = vh[0] * inv, t1v[2] = 0.0;
    }
    double t2v[3] = {vh[1] * t1v[2] - vh[2] * t1v[1], vh[2] * t1v[0] - vh[0] * t1v[2], vh[0] * t1v[1] - vh[1] * t1v[0]};
    double r = sqrt(u1), phi = 2.0 * MATH_PI * u2;
    double p1 = r * cos(phi), p2 = r * sin(phi), sh = 0.5 * (1.0 + vh[2]);
    p2 = (1.0 - sh) * sqrt(fmax(1.0 - p1 * p1, 0.0)) + sh * p2;
    double p3 = sqrt(fmax(1.0 - p1 * p1 - p2 * p2, 0.0));
    double nh[3];
    for (int k = 0; k < 3; k++)
        nh[k] = p1 * t1v[k] + p2 * t2v[k] + p3 * vh[k];
    double ne[3] = {alpha * nh[0], alpha * nh[1], fmax(nh[2], 0.0)};
    double nel = sqrt(dot3(ne, ne));
    if (!(nel > 0.0))
        return false;
    double h[3];
    for (int k = 0; k < 3; k++)
        h[k] = (ne[0] * t[k] + ne[1] * b[k] + ne[2] * axis[k]) / nel;
    double v_dot_h = dot3(v, h);
    for (int k = 0; k < 3; k++)
        l[k] = 2.0 * v_dot_h * h[k] - v[k];
    if (!(dot3(n, l) > 0.0) && !(coat && dot3(m->clearcoat_normal, l) > 0.0))
        return false;
    double p_base = vndf_pdf_l(n, v, l, fmax(m->roughness * m->roughness, BRDF_MIN_ALPHA));
    *pdf = coat ? 0.5 * p_base + 0.5 * vndf_pdf_l(m->clearcoat_normal, v, l,
                                                  fmax(m->clearcoat_roughness * m->clearcoat_roughness, BRDF_MIN_ALPHA))
                : p_base;
    return *pdf > 0.0 && isfinite(*pdf);
}

bool brdf_quadrature_direction(int k, int side, double alpha, const double v[3], double l[3], double h[3],
                               double *pdf)
{
    int j = k % (side * side);
    double u1 = (j / side + 0.5) / side, u2 = (j % side + 0.5) / side;
    if (k < side * side) {
        /* Walter et al. 2007 eqs. 35-36: tan^2 theta_h = alpha^2 u1 / (1 - u1) */
        double t2 = alpha * alpha * u1 / (1.0 - u1), c = 1.0 / sqrt(1.0 + t2), s = sqrt(fmax(1.0 - c * c, 0.0));
        double phi = 2.0 * MATH_PI * u2, m[3] = {s * cos(phi), s * sin(phi), c};
        double vm = dot3(v, m);
        for (int q = 0; q < 3; q++)
            l[q] = 2.0 * vm * m[q] - v[q];
    } else {
        double r = sqrt(u1), phi = 2.0 * MATH_PI * u2;
        l[0] = r * cos(phi), l[1] = r * sin(phi), l[2] = sqrt(fmax(1.0 - u1, 0.0));
    }
    if (!(l[2] > 0.0) || !(v[2] > 0.0))
        return false;
    for (int q = 0; q < 3; q++)
        h[q] = v[q] + l[q];
    double hl = sqrt(dot3(h, h));
    if (!(hl > 1e-12))
        return false;
    for (int q = 0; q < 3; q++)
        h[q] /= hl;
    double vh = fmin(fabs(dot3(v, h)), 1.0);
    double d = brdf_ggx_d(h[2], h[0] * h[0] + h[1] * h[1], alpha);
    *pdf = 0.5 * d * h[2] / (4.0 * fmax(vh, 1e-12)) + 0.5 * l[2] / MATH_PI;
    return true;
}

/* The three integrals at (NdotV, alpha), by brdf_quadrature_direction. */
static void ambient_integrals(double n_dot_v, double alpha, double out[3])
{
    enum { SIDE = 48 };
    double v[3] = {sqrt(fmax(1.0 - n_dot_v * n_dot_v, 0.0)), 0.0, n_dot_v};
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < 2 * SIDE * SIDE; k++) {
        double l[3], h[3], pdf;
        if (!brdf_quadrature_direction(k, SIDE, alpha, v, l, h, &pdf))
            continue;
        double vh = fmin(fabs(dot3(v, h)), 1.0);
        double d = brdf_ggx_d(h[2], h[0] * h[0] + h[1] * h[1], alpha);
        double w = pow(1.0 - vh, 5.0), dv = d * brdf_smith_v(l[2], n_dot_v, alpha);
        sum[0] += w * l[2] / MATH_PI / pdf;
        sum[1] += dv * l[2] / pdf;
        sum[2] += w * dv * l[2] / pdf;
    }
    for (int q = 0; q < 3; q++)
        out[q] = sum[q] / (2.0 * SIDE * SIDE);
}

static float ambient_table[BRDF_TABLE_SIZE * BRDF_TABLE_SIZE * 3];
static pthread_once_t ambient_once = PTHREAD_ONCE_INIT;

static void ambient_table_build(void)
{
    for (int r = 0; r < BRDF_TABLE_SIZE; r++)
        for (int c = 0; c < BRDF_TABLE_SIZE; c++) {
            double roughness = pow((double)r / (BRDF_TABLE_SIZE - 1), 2.0), n_dot_v = pow((double)c / (BRDF_TABLE_SIZE - 1), 2.0);
            double terms[3];
            /* NdotV 0 (a surface seen edge-on) takes the nearest view that sees it */
            ambient_integrals(fmax(n_dot_v, 1e-3), fmax(roughness * roughness, BRDF_MIN_ALPHA), terms);
            for (int q = 0; q < 3; q++)
                ambient_table[(r * BRDF_TABLE_SIZE + c) * 3 + q] = (float)terms[q];
        }
}

const float *brdf_ambient_table(void)
{
    pthread_once(&ambient_once, ambient_table_build);
    return ambient_table;
}

/* (Wd, S0, S1) at (NdotV, roughness), bilinear between the table's texels
 * (common/brdf.glsl's brdf_ambient_terms, the same arithmetic in float) */
static void ambient_terms(double n_dot_v, double roughness, double out[3])
{
    const float *t = brdf_ambient_table();
    double x = sqrt(fmin(fmax(n_dot_v, 0.0), 1.0)) * (BRDF_TABLE_SIZE - 1); /* columns by sqrt(NdotV) */
    double y = sqrt(fmin(fmax(roughness, 0.0), 1.0)) * (BRDF_TABLE_SIZE - 1); /* rows by sqrt(roughness) */
    int x0 = (int)fmin(floor(x), BRDF_TABLE_SIZE - 2), y0 = (int)fmin(floor(y), BRDF_TABLE_SIZE - 2);
    double fx = x - x0, fy = y - y0;
    for (int q = 0; q < 3; q++) {
        double a = t[(y0 * BRDF_TABLE_SIZE + x0) * 3 + q], b = t[(y0 * BRDF_TABLE_SIZE + x0 + 1) * 3 + q];
        double c = t[((y0 + 1) * BRDF_TABLE_SIZE + x0) * 3 + q], d = t[((y0 + 1) * BRDF_TABLE_SIZE + x0 + 1) * 3 + q];
        out[q] = (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
    }
}

double brdf_specular_albedo(double n_dot_v, double roughness, double f0)
{
    double t[3];
    ambient_terms(n_dot_v, roughness, t);
    return f0 * t[1] + (1.0 - f0) * t[2];
}

void brdf_ambient_albedo(const double n[3], const double v[3], const struct brdf_material *m, double out[3])
{
    double n_dot_v = fmin(fmax(dot3(n, v), 0.0), 1.0), t[3];
    ambient_terms(n_dot_v, m->roughness, t);
    double r0 = (m->ior - 1.0) / (m->ior + 1.0), f0[3], f0_max = 0.0;
    for (int k = 0; k < 3; k++) {
        f0[k] = fmin(r0 * r0 * m->specular_color[k], 1.0);
        f0_max = fmax(f0_max, f0[k]);
    }
    for (int k = 0; k < 3; k++) {
        double c = m->base_color[k], s = m->specular;
        /* the diffuse lobe weighed by 1 - s E(NdotV) (brdf.h), E the
         * specular lobe's albedo at the largest F0 */
        double dielectric = c * (1.0 - s * (f0_max * t[1] + (1.0 - f0_max) * t[2])) +
                            s * (f0[k] * t[1] + (1.0 - f0[k]) * t[2]);
        double metal = c * t[1] + (1.0 - c) * t[2];
        out[k] = dielectric + m->metallic * (metal - dielectric);
    }
    double share = brdf_clearcoat_share(v, m);
    if (share > 0.0) {
        double tc[3];
        ambient_terms(fmin(fmax(dot3(m->clearcoat_normal, v), 0.0), 1.0), m->clearcoat_roughness, tc);
        for (int k = 0; k < 3; k++)
            out[k] = (1.0 - share) * out[k] + share * tc[1];
    }
}

void brdf_diffuse_albedo(const double n[3], const double v[3], const struct brdf_material *m, double out[3])
{
    double n_dot_v = dot3(n, v);
    double r0 = (m->ior - 1.0) / (m->ior + 1.0), f0_max = 0.0;
    for (int k = 0; k < 3; k++)
        f0_max = fmax(f0_max, fmin(r0 * r0 * m->specular_color[k], 1.0));
    double weight = 1.0 - m->specular * brdf_specular_albedo(n_dot_v, m->roughness, f0_max);
    double share = brdf_clearcoat_share(v, m);
    for (int k = 0; k < 3; k++)
        out[k] = (1.0 - share) * (1.0 - m->metallic) * m->base_color[k] * weight;
}
