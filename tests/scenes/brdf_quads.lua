-- glTF's metallic-roughness BRDF against its closed form (issue 50):
-- tests/data/brdf_quads.gltf's six quads (metals and dielectrics at two
-- roughness values, a metallicRoughnessTexture half metal, half dielectric,
-- and KHR_materials_specular with KHR_materials_ior) in the xz plane, seen by an orthographic camera from
-- v = (0, 2, 1) / sqrt 5 and lit by a sun from l = (1, 5, -2) / sqrt 30, so
-- every pixel of a quad has one n, v and l. --set ambient=A: a grey sky
-- (on the diffuse lobe, by the occlusion); background=B: a uniform grey
-- environment (which the specular lobes reflect); both 0 by default;
-- glossy=true: glossy_reflection after shade.
local c = require "caustica"
local v = {0, 2, 1}
local scene = c.scene {
  camera = c.camera { eye = {3.75 + 4 * v[1], 4 * v[2], 4 * v[3]}, target = {3.75, 0, 0}, ortho = { width = 10 },
                      near = 0.5, far = 20 },
  background = { c.param("background", 0), c.param("background", 0), c.param("background", 0) },
  ambient = { c.param("ambient", 0), c.param("ambient", 0), c.param("ambient", 0) },
}
scene:add(c.light.directional { direction = {-1, -5, 2}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.load "../data/brdf_quads.gltf" })
local g = c.graph()
g:add("shade", c.pass.shade {})
if c.param("glossy", false) then
  g:add("glossy", c.pass.glossy_reflection { color = "shade.color" })
  g:output("glossy.color")
else
  g:output("shade.color")
end
return { scene = scene, graph = g, size = {160, 80} }
