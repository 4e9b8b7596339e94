// The glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification, Appendix B
// "BRDF Implementation"; KHR_materials_specular and KHR_materials_ior for
// the dielectric's reflectance). Its C twin is src/core/brdf.c, line for
// line; tests/unit/test_shading.c holds the two to each other on a grid and
// checks the white furnace. See src/core/brdf.h for the formulas.
struct BrdfMaterial {
    vec3 base_color;
    float metallic;
    float roughness;      // perceptual: alpha = roughness^2
    float ior;            // 1.5 without KHR_materials_ior
    float specular;       // 1 without KHR_materials_specular
    vec3 specular_color;  // 1 without it
    float clearcoat;      // KHR_materials_clearcoat's weight, 0 without it
    float clearcoat_roughness;
    vec3 clearcoat_normal; // unit; read only where clearcoat > 0
};

const float BRDF_MIN_ALPHA = 1e-4; // roughness 0: a highlight 1e-4 wide, never 0 / 0 (core/brdf.h)
const float BRDF_PI = 3.14159265358979;

// GGX's D for NdotH and sin2 = |n x h|^2 (1 - NdotH^2 in float is off by
// 20x at a roughness-0 highlight's centre; the cross product is exact)
float brdf_ggx_d(float n_dot_h, float sin2, float alpha)
{
    float a2 = alpha * alpha;
    float k = n_dot_h * n_dot_h * a2 + max(sin2, 0.0);
    return n_dot_h > 0.0 ? a2 / (BRDF_PI * k * k) : 0.0;
}

// Smith's height-correlated visibility G2 / (4 NdotL NdotV)
float brdf_smith_v(float n_dot_l, float n_dot_v, float alpha)
{
    float a2 = alpha * alpha;
    float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    float s = gv + gl;
    return s > 0.0 ? 0.5 / s : 0.0;
}

// The uniform sky on a glTF surface: core/brdf.h's three integrals (Wd, S0,
// S1) of (NdotV, roughness), tabulated once on the CPU (brdf_ambient_table,
// BRDF_TABLE_SIZE^2, bound by the renderer) and read here bilinearly by the
// same arithmetic as brdf.c's ambient_terms.
uniform sampler2D u_brdf_table;
const int BRDF_TABLE_SIZE = 32;

vec3 brdf_ambient_terms(float n_dot_v, float roughness)
{
    float x = sqrt(clamp(n_dot_v, 0.0, 1.0)) * float(BRDF_TABLE_SIZE - 1); // columns by sqrt(NdotV)
    float y = sqrt(clamp(roughness, 0.0, 1.0)) * float(BRDF_TABLE_SIZE - 1); // rows by sqrt(roughness)
    int x0 = int(min(floor(x), float(BRDF_TABLE_SIZE - 2))), y0 = int(min(floor(y), float(BRDF_TABLE_SIZE - 2)));
    float fx = x - float(x0), fy = y - float(y0);
    vec3 a = texelFetch(u_brdf_table, ivec2(x0, y0), 0).rgb, b = texelFetch(u_brdf_table, ivec2(x0 + 1, y0), 0).rgb;
    vec3 c = texelFetch(u_brdf_table, ivec2(x0, y0 + 1), 0).rgb, d = texelFetch(u_brdf_table, ivec2(x0 + 1, y0 + 1), 0).rgb;
    vec3 top = a + (b - a) * fx;
    return top + ((c + (d - c) * fx) - top) * fy;
}

// The specular lobe's directional albedo f0 S0 + (1 - f0) S1 (core/brdf.h)
float brdf_specular_albedo(float n_dot_v, float roughness, float f0)
{
    vec3 t = brdf_ambient_terms(n_dot_v, roughness);
    return f0 * t.y + (1.0 - f0) * t.z;
}

// f(v, l) at unit n, v towards the viewer, l towards the light; 0 below.
// The diffuse lobe takes 1 - specular x the specular lobe's albedo from
// this view, not Appendix B's 1 - max(F(VdotH)) (core/brdf.h: energy
// conserving in the white furnace).
vec3 brdf_gltf(vec3 n, vec3 v, vec3 l, BrdfMaterial m)
{
    float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return vec3(0.0);
    vec3 h = v + l;
    float hl = length(h);
    if (!(hl > 1e-12))
        return vec3(0.0);
    h /= hl;
    float n_dot_h = min(dot(n, h), 1.0), v_dot_h = min(abs(dot(v, h)), 1.0);
    float alpha = max(m.roughness * m.roughness, BRDF_MIN_ALPHA);
    vec3 c = cross(n, h);
    float spec = brdf_ggx_d(n_dot_h, dot(c, c), alpha) * brdf_smith_v(n_dot_l, n_dot_v, alpha);
    float w = pow(1.0 - v_dot_h, 5.0);
    float r0 = (m.ior - 1.0) / (m.ior + 1.0);
    vec3 f0 = min(r0 * r0 * m.specular_color, vec3(1.0));
    vec3 fd = f0 + (1.0 - f0) * w;
    float f0_max = max(f0.r, max(f0.g, f0.b));
    float diffuse_weight = 1.0 - m.specular * brdf_specular_albedo(n_dot_v, m.roughness, f0_max);
    vec3 dielectric = diffuse_weight * m.base_color / BRDF_PI + m.specular * fd * spec;
    vec3 metal = (m.base_color + (1.0 - m.base_color) * w) * spec;
    return dielectric + m.metallic * (metal - dielectric);
}

// The coat's share of the view, clearcoat x Fc (KHR_materials_clearcoat's
// fresnel_coat: f0 of IOR 1.5 at |n_c . v|); 0 without a coat
float brdf_clearcoat_share(vec3 v, BrdfMaterial m)
{
    if (!(m.clearcoat > 0.0))
        return 0.0;
    float c = min(abs(dot(m.clearcoat_normal, v)), 1.0);
    return m.clearcoat * (0.04 + 0.96 * pow(1.0 - c, 5.0));
}

// The coat's lobe D_c V_c (n_c . l), 0 below n_c
float brdf_clearcoat_lobe_cos(vec3 v, vec3 l, BrdfMaterial m)
{
    vec3 n = m.clearcoat_normal;
    float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return 0.0;
    vec3 h = v + l;
    float hl = length(h);
    if (!(hl > 1e-12))
        return 0.0;
    h /= hl;
    float alpha = max(m.clearcoat_roughness * m.clearcoat_roughness, BRDF_MIN_ALPHA);
    vec3 c = cross(n, h);
    return brdf_ggx_d(min(dot(n, h), 1.0), dot(c, c), alpha) * brdf_smith_v(n_dot_l, n_dot_v, alpha) * n_dot_l;
}

// f cos with the coat (core/brdf.h): what a light's arrival (irradiance at
// normal incidence) from l is multiplied by towards v
vec3 brdf_gltf_cos(vec3 n, vec3 v, vec3 l, BrdfMaterial m)
{
    vec3 f = brdf_gltf(n, v, l, m);
    float c = max(dot(n, l), 0.0);
    float share = brdf_clearcoat_share(v, m);
    float coat = share > 0.0 ? share * brdf_clearcoat_lobe_cos(v, l, m) : 0.0;
    return (1.0 - share) * f * c + coat;
}

// The BRDF's directional albedo for normal n and view v (what a sky of
// radiance 1 returns), with the coat's
vec3 brdf_ambient_albedo(vec3 n, vec3 v, BrdfMaterial m)
{
    vec3 t = brdf_ambient_terms(dot(n, v), m.roughness);
    float r0 = (m.ior - 1.0) / (m.ior + 1.0);
    vec3 f0 = min(r0 * r0 * m.specular_color, vec3(1.0));
    float f0_max = max(f0.r, max(f0.g, f0.b));
    vec3 c = m.base_color;
    float s = m.specular;
    vec3 dielectric = c * (1.0 - s * (f0_max * t.y + (1.0 - f0_max) * t.z)) + s * (f0 * t.y + (1.0 - f0) * t.z);
    vec3 metal = c * t.y + (1.0 - c) * t.z;
    vec3 albedo = dielectric + m.metallic * (metal - dielectric);
    float share = brdf_clearcoat_share(v, m);
    if (share > 0.0)
        albedo = (1.0 - share) * albedo + share * brdf_ambient_terms(dot(m.clearcoat_normal, v), m.clearcoat_roughness).y;
    return albedo;
}

// The diffuse lobe's albedo for light from no one direction (caustics),
// less what the coat reflects
vec3 brdf_diffuse_albedo(vec3 n, vec3 v, BrdfMaterial m)
{
    float r0 = (m.ior - 1.0) / (m.ior + 1.0);
    vec3 f0 = min(r0 * r0 * m.specular_color, vec3(1.0));
    float f0_max = max(f0.r, max(f0.g, f0.b));
    float weight = 1.0 - m.specular * brdf_specular_albedo(dot(n, v), m.roughness, f0_max);
    return (1.0 - brdf_clearcoat_share(v, m)) * (1.0 - m.metallic) * m.base_color * weight;
}

// The specular lobes' albedos apart (what they reflect of a uniform sky):
// the base lobe's, and a clearcoat's (0 without one)
void brdf_specular_albedos(vec3 n, vec3 v, BrdfMaterial m, out vec3 base, out float coat)
{
    float share = brdf_clearcoat_share(v, m);
    coat = share > 0.0 ? share * brdf_ambient_terms(dot(m.clearcoat_normal, v), m.clearcoat_roughness).y : 0.0;
    base = max(brdf_ambient_albedo(n, v, m) - brdf_diffuse_albedo(n, v, m) - vec3(coat), vec3(0.0));
}
