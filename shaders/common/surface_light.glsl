// The one lighting function of diffuse surfaces (issue 50): every pass that
// lights a surface calls it (shade, the distance map, the impostors, the
// slices of sliced_refraction, refraction's diffuse share of partly
// transmissive glass), so a floor seen directly, through glass by way of
// the distance map or an impostor, or in a slice is lit alike. Its C twin
// is src/core/shading.c (shading_diffuse_radiance, shading_light_arrival),
// which the reference lights with; tests/unit/test_shading.c holds the two
// to each other on a grid, as values_test holds fresnel.glsl.
//
// Needs common/frame.glsl, common/lighting.glsl, common/shadows.glsl,
// common/medium.glsl and, included before it, common/material.glsl for
// surface_light_gltf and surface_light_material: a pass binds its shadow maps (shadow_inputs_bind; none
// gives u_shadow_total = 0, unshadowed) and the medium (medium_gpu_bind;
// none gives u_medium = 0, transmittance 1).

// Irradiance at p with normal n from light i: shadowed by the maps bound,
// attenuated by the medium between p and the light; `to_light` receives
// the unit direction towards it.
vec3 surface_irradiance_from(int i, vec3 p, vec3 n, out vec3 to_light)
{
    float dist;
    vec3 irr = light_irradiance(i, p, n, to_light, dist);
    if (!(max(irr.r, max(irr.g, irr.b)) > 0.0))
        return vec3(0.0);
    return irr * visibility_color(i, p, n, to_light) * medium_transmittance_ray(p, to_light, dist);
}

// The same at normal incidence (no cosine), for a surface that weighs it
// by cosines of its own (a clearcoat's normal); 0 where neither n nor
// n_other faces the light.
vec3 surface_arrival_from(int i, vec3 p, vec3 n, vec3 n_other, out vec3 to_light)
{
    float dist;
    vec3 e = light_arrival(i, p, to_light, dist);
    if (!(max(e.r, max(e.g, e.b)) > 0.0) || !(max(dot(n, to_light), dot(n_other, to_light)) > 0.0))
        return vec3(0.0);
    return e * visibility_color(i, p, n, to_light) * medium_transmittance_ray(p, to_light, dist);
}

// The same from every light.
vec3 surface_irradiance(vec3 p, vec3 n)
{
    vec3 e = vec3(0.0), to_light;
    for (int i = 0; i < u_counts.x; i++)
        e += surface_irradiance_from(i, p, n, to_light);
    return e;
}

// Lambert's radiance for irradiance e (the lights', plus any caustic
// irradiance the pass has), the ambient sky and the surface's own emission.
vec3 surface_diffuse_radiance(vec3 albedo, vec3 e, vec3 emission)
{
    return albedo / PI * e + albedo * u_ambient.rgb + emission;
}

// A diffuse surface at p, normal n: `caustic` is the caustic irradiance
// where the pass has it (shade reads the caustic passes' images, which are
// the camera's view; a pass that sees the surface another way passes 0, and
// docs/ARCHITECTURE.md says which).
vec3 surface_light_diffuse(vec3 p, vec3 n, vec3 albedo, vec3 emission, vec3 caustic)
{
    return surface_diffuse_radiance(albedo, surface_irradiance(p, n) + caustic, emission);
}

#ifdef MATERIAL_GLSL
// (the material functions below read common/material.glsl's uniforms and
// the mesh's texture coordinates: only where it was included first; the
// slices and refraction's diffuse share draw Lambert surfaces of u_color)

// A glTF surface (material.pbr) at p, normal n, seen from direction v
// (unit, towards the viewer): each light's irradiance times the BRDF, the
// ambient sky times the diffuse lobe's albedo and the specular lobes'
// reflection of the environment (surface_glossy_environment), both times
// the occlusion, the caustic irradiance times the diffuse lobe's albedo / pi
// (it comes from no one direction), and the emission. The reference: ref_sppm.c, the same
// terms by core/brdf.c.
// The environment seen about direction r by a glossy lobe of GGX
// roughness `roughness`: the background colour, or the environment cube's
// mip level whose texels span the lobe, about 2 alpha radians (the mips
// are box-filtered: a stand-in for the lobe's own filter, which the
// reference samples; docs/GLTF.md)
vec3 environment_glossy(vec3 r, float roughness)
{
    if (u_background.w <= 0.5)
        return u_background.rgb;
    float size = float(textureSize(u_environment, 0).x);
    float alpha = roughness * roughness;
    float lod = log2(max(2.0 * alpha * size / 1.5708, 1.0));
    return textureLod(u_environment, r, min(lod, float(textureQueryLevels(u_environment) - 1))).rgb;
}

// How much of a lobe about mirror direction r a surface of normal ng (the
// geometry's, before its normal map) does not hide: a direction a normal
// map turns under the surface meets the surface itself, which the
// reference's traced rays find (black rings about NormalTangentTest's
// bumps on its metal tiles). The horizon fade of Russell 2015, "Horizon
// Occlusion for Normal Mapped Reflections" (Marmoset): (1 + r . ng)^2,
// clamped; 1 without ng. NormalTangentTest 0.083 -> 0.069 of the
// reference, NormalTangentMirrorTest 0.117 -> 0.100.
float surface_horizon(vec3 r, vec3 ng)
{
    if (!(dot(ng, ng) > 0.0))
        return 1.0;
    float h = clamp(1.0 + dot(r, ng), 0.0, 1.0);
    return h * h;
}

// What the specular lobes (the base's and a clearcoat's) reflect of the
// environment towards v: each lobe's albedo times the environment about
// its mirror direction (the split sum), faded under the geometry's
// horizon; the reference traces them.
vec3 surface_glossy_environment(vec3 n, vec3 v, BrdfMaterial m)
{
    vec3 base;
    float coat;
    brdf_specular_albedos(n, v, m, base, coat);
    vec3 glossy = vec3(0.0);
    if (coat > 0.0) {
        vec3 rc = reflect(-v, m.clearcoat_normal);
        glossy = coat * environment_glossy(rc, m.clearcoat_roughness) * surface_horizon(rc, material_geometry_normal);
    }
    vec3 r = reflect(-v, n);
    return glossy + base * environment_glossy(r, m.roughness) * surface_horizon(r, material_geometry_normal);
}

vec3 surface_light_gltf(vec3 p, vec3 n, vec3 v, BrdfMaterial m, float occlusion, vec3 emission, vec3 caustic)
{
    vec3 radiance = vec3(0.0), to_light;
    vec3 coat_n = m.clearcoat > 0.0 ? m.clearcoat_normal : n; // (the coat's own normal may face a light n does not)
    for (int i = 0; i < u_counts.x; i++) {
        vec3 e = surface_arrival_from(i, p, n, coat_n, to_light);
        radiance += brdf_gltf_cos(n, v, to_light, m) * e;
    }
    vec3 diffuse = brdf_diffuse_albedo(n, v, m);
    return radiance + (u_ambient.rgb * diffuse + surface_glossy_environment(n, v, m)) * occlusion +
           caustic * diffuse / PI + emission;
}

// The surface of the object being drawn (common/material.glsl's uniforms
// and textures): glTF's BRDF in the program's GLTF_BRDF variant, which
// draws the materials with pbr (renderer_draw_lit), Lambert otherwise; v
// (unit, towards the viewer) matters only to the BRDF. A variant, not a
// branch on a uniform: llvmpipe runs both sides of a branch.
vec3 surface_light_material(vec3 p, vec3 n, vec3 v, vec3 color, vec3 emission, vec3 caustic)
{
#ifdef GLTF_BRDF
    return surface_light_gltf(p, n, v, material_brdf(color), material_occlusion(), material_emission(emission),
                              caustic);
#else
    return surface_light_diffuse(p, n, material_albedo(color), material_emission(emission), caustic);
#endif
}
#endif
