/* The glTF 2.0 metallic-roughness BRDF in double precision (glTF 2.0
 * specification, Appendix B "BRDF Implementation"; KHR_materials_specular
 * and KHR_materials_ior for the dielectric's reflectance): the C twin of
 * shaders/common/brdf.glsl, held to it by tests/unit/test_shading.c on a
 * grid of roughness, metallic and angles, which also checks the white
 * furnace (a white surface under a uniform white sky returns at most 1).
 *
 *   f = mix(dielectric, metal, metallic)
 *   metal      = F_schlick(base_color, VdotH) * D * V
 *   dielectric = (1 - specular * E(NdotV)) * base_color / pi + specular * F * D * V,
 *                F = F_schlick(min(((ior - 1) / (ior + 1))^2 * specular_color, 1), VdotH)
 *   D = Trowbridge-Reitz (GGX), alpha = roughness^2;
 *   V = Smith's height-correlated joint masking-shadowing over 4 NdotL NdotV;
 *   E(NdotV) = integral(max(F) D V cos): the specular lobe's directional
 *   albedo at the largest F0 (brdf_specular_albedo, from the table below).
 *
 * The diffuse lobe takes 1 - what the specular lobe reflects from this
 * view, not Appendix B's 1 - max(F(VdotH)) per light (its fresnel_mix,
 * which the appendix gives as one informative approximation): that one is
 * not energy conserving, a white dielectric in a white furnace returned up
 * to 1.84 at grazing views (cos 0.02) and 1.13 at cos 0.3, roughness 0.25;
 * with the albedo it returns at most 1 (the albedo scaling of Kulla and
 * Conty 2017, "Revisiting physically based shading at Imageworks"). The
 * two agree where F(VdotH) is near F0 across the lobe, at views near the
 * normal.
 *
 * KHR_materials_clearcoat lays a second lobe over that, with its own
 * normal n_c and roughness (the extension's fresnel_coat):
 *   f_coated = (1 - clearcoat Fc) f + clearcoat Fc D_c V_c,
 *   Fc = 0.04 + 0.96 (1 - |n_c . v|)^5 (the coat's IOR 1.5),
 * D_c and V_c about n_c with alpha_c = clearcoat_roughness^2. Fc depends on
 * the view alone, so the coat takes from the base what it reflects.
 *
 * The first brick of issue 50's material model: what draws with it is
 * listed in docs/GLTF.md. */
#ifndef CAUSTICA_BRDF_H
#define CAUSTICA_BRDF_H

#include <stdbool.h>

struct brdf_material {
    double base_color[3];     /* linear RGB (texture x factor x COLOR_0) */
    double metallic;          /* [0, 1] */
    double roughness;         /* perceptual, [0, 1]; alpha = roughness^2 */
    double ior;               /* KHR_materials_ior, 1.5 without it */
    double specular;          /* KHR_materials_specular's specularFactor, 1 without it */
    double specular_color[3]; /* its specularColorFactor, 1 without it */
    double clearcoat;         /* KHR_materials_clearcoat's weight, 0 without it */
    double clearcoat_roughness;
    double clearcoat_normal[3]; /* unit, towards the viewer's side; read only where clearcoat > 0 */
};

/* The glTF material without extensions: ior 1.5, specular 1, white specular colour, no clearcoat. */
struct brdf_material brdf_material_default(double r, double g, double b, double metallic, double roughness);

/* The least alpha evaluated: GGX's D is a Dirac delta at alpha 0; a
 * roughness of 0 is drawn as alpha 1e-4 (a highlight 1e-4 radians wide),
 * both here and in GLSL, so it never divides 0 by 0. */
#define BRDF_MIN_ALPHA 1e-4

/* GGX's normal distribution D(h) for NdotH and sin2 = 1 - NdotH^2, which
 * the caller takes as |n x h|^2: near the peak that is exact to float's
 * precision where 1 - NdotH^2 is not (the GPU's D at roughness 0 was off by
 * 20x at the highlight's centre with 1 - NdotH^2). */
double brdf_ggx_d(double n_dot_h, double sin2, double alpha);
/* Smith's height-correlated visibility V = G2 / (4 NdotL NdotV). */
double brdf_smith_v(double n_dot_l, double n_dot_v, double alpha);

/* f(v, l) at unit normal n, unit v (towards the viewer) and unit l
 * (towards the light), per colour channel; 0 where l or v is below the
 * surface. Never a NaN or Inf for unit inputs. */
void brdf_gltf(const double n[3], const double v[3], const double l[3], const struct brdf_material *m, double f[3]);

/* The specular lobe's directional albedo f0 S0 + (1 - f0) S1 at (NdotV,
 * roughness) from the ambient table (the diffuse lobe's weight is 1 -
 * specular x this at the largest F0). */
double brdf_specular_albedo(double n_dot_v, double roughness, double f0);

/* The coat's share of the view, clearcoat x Fc (0 without a coat). */
double brdf_clearcoat_share(const double v[3], const struct brdf_material *m);

/* What a light of radiance-times-solid-angle 1 from l sends towards v:
 * f (n . l) with the coat, (1 - share) f (n . l) + share D_c V_c (n_c . l),
 * each cosine 0 below its own normal. A light's arrival (irradiance at
 * normal incidence) times this is its reflected radiance; lights are drawn
 * by it in both renderers. */
void brdf_gltf_cos(const double n[3], const double v[3], const double l[3], const struct brdf_material *m,
                   double out[3]);

/* The specular lobes' share of brdf_gltf_cos (the base's GGX lobe and
 * the coat's, without the diffuse lobe): what the environment and the
 * scene reflect glossily towards v (docs/GLTF.md). */
void brdf_gltf_specular_cos(const double n[3], const double v[3], const double l[3], const struct brdf_material *m,
                            double out[3]);
/* A direction l for brdf_gltf_specular_cos from three uniform numbers:
 * GGX's visible normals of the base lobe (Heitz 2018), or of the coat's
 * with probability 1/2 where there is one, reflected about v; *pdf the
 * mixture's density of l (solid angle). A bare lobe's weight f cos / pdf
 * is then F G2 / G1, at most 1 (drawing half vectors by D cos alone gave
 * weights without bound at grazing half vectors: 2% short of a rough
 * metal's albedo at 20000 samples). False where l falls below n (it adds
 * nothing) or v below the lobe's normal. */
bool brdf_sample_specular(const double n[3], const double v[3], const struct brdf_material *m, double u1, double u2,
                          double u3, double l[3], double *pdf);

/* Direction k (0 <= k < 2 side^2) of the deterministic quadrature that
 * integrates f cos over the hemisphere about n = +z for a view v (unit, v.z
 * > 0): the first side^2 reflect v about GGX half vectors drawn from D(h)
 * NdotH on a side x side grid of (u1, u2), the rest are cosine-distributed
 * on the same grid; combined by the balance heuristic, so each direction's
 * weight is f cos / *pdf with *pdf = 0.5 p_ggx + 0.5 p_cos, over 2 side^2.
 * l and the unit half vector h of v and l; false where l is below the
 * surface (it adds nothing). The ambient table below and
 * tests/unit/test_shading.c's furnace use it. */
bool brdf_quadrature_direction(int k, int side, double alpha, const double v[3], double l[3], double h[3],
                               double *pdf);

/* The uniform sky's light (the scene's ambient term, radiance A from every
 * direction above) on a glTF surface: A x the BRDF's directional albedo
 * integral(f(v, l) cos dl), which is linear in three integrals of (NdotV,
 * alpha) alone (w = (1 - VdotH)^5):
 *   Wd = integral(w cos / pi), S0 = integral(D V cos), S1 = integral(w D V cos),
 *   albedo = mix(c (1 - s E) + s (f0 S0 + (1 - f0) S1), b S0 + (1 - b) S1, metallic),
 *   E = f0max S0 + (1 - f0max) S1 (Wd, Appendix B's diffuse weight, is no longer used:
 *   kept in the table's layout).
 * The three are tabulated once, BRDF_TABLE_SIZE^2 over NdotV and roughness
 * in [0, 1] (a deterministic quadrature of GGX half vectors and cosine
 * directions, as tests/unit/test_shading.c's furnace), and read bilinearly:
 * the GPU reads the same table texel for texel (renderer_brdf_table,
 * common/brdf.glsl's brdf_ambient), so both renderers give the sky the
 * same response. */
#define BRDF_TABLE_SIZE 32
/* The table: BRDF_TABLE_SIZE^2 x (Wd, S0, S1), row r = roughness
 * r / (size - 1), column c = NdotV c / (size - 1). Built on first use
 * (thread-safe), never freed. */
const float *brdf_ambient_table(void);
/* The directional albedo per channel for unit normal n and view v (the
 * table read bilinearly), with the coat: (1 - share) albedo +
 * share S0(n_c . v, clearcoat_roughness). */
void brdf_ambient_albedo(const double n[3], const double v[3], const struct brdf_material *m, double out[3]);
/* The share of light the diffuse lobe sends back, per channel, for
 * irradiance that arrives from no one direction (caustics, photons): the
 * Lambert albedo (1 - metallic) c (1 - s E(NdotV)), as f's diffuse lobe,
 * less what the coat reflects (x (1 - share)). Both renderers weigh
 * caustic irradiance on a glTF surface by it. */
void brdf_diffuse_albedo(const double n[3], const double v[3], const struct brdf_material *m, double out[3]);

#endif
