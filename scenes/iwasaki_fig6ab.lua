-- Iwasaki et al., Fig. 6(a)(b): a glass ball in front of the Happy Buddha
-- casting caustics on it; the buddha, caustics included, seen through the
-- ball through sliced object images (§3, [13]: the caustics are in the image
-- they are made from). A point light. --set view=b for the second view.
local c = require "caustica"
local scene = c.scene {
  camera = c.param("view", "a") == "b" and c.camera { eye = {-1.2, 0.6, 1.9}, target = {0, 0.25, 0}, fov = 40 }
                                        or c.camera { eye = {0.3, 0.55, 2.3}, target = {0, 0.3, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.04},
}
local lamp = scene:add(c.light.point { position = {0.9, 2.2, 2.0}, intensity = {9, 8.6, 8} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse { color = {0.6, 0.6, 0.6} } })
local buddha = c.mesh.load(c.asset "buddha_60k.glb")
scene:add(c.object { mesh = buddha, material = c.material.diffuse { color = {0.85, 0.75, 0.55} },
                     position = {0, -1.1 * buddha.bounds[1][2], -0.1}, scale = {1.1, 1.1, 1.1} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.2, segments = 48 }, position = {0.15, 0.5, 0.45},
                     material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("caustics", c.pass.illumination_textures { light = lamp })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
-- the refracted view: --set refraction=sliced (the paper's sliced object images), layered, or huqin
local refraction = c.param("refraction", "sliced")
if refraction == "sliced" then
  g:add("glass", c.pass.sliced_refraction { color = "shade.color", slices = 6 })
elseif refraction == "layered" then
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
else
  g:add("glass", c.pass.refraction { color = "shade.color" })
end
g:output(c.param("output", "glass.color"))
return { scene = scene, graph = g, size = {640, 480} }
