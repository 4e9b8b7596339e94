-- A cut-out (glTF alphaMode MASK): a 1 x 1 quad (tests/data/cutout_quad.gltf,
-- an orange checker whose dark squares have alpha 0) 0.6 above a white
-- floor, under a sun straight above and seen from above at an angle: the
-- floor shows through the holes, and the shadow is a checker of squares
-- 0.25 wide. --set mask=false: the same quad opaque (alpha_cutoff 0).
-- --set blend=true: tests/data/blend_quad.gltf instead, alphaMode BLEND at
-- alpha 0.5 (the floor half seen through it, a half shadow).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 2.2, 1.6}, target = {0, 0.2, 0}, fov = 40 },
  background = {0.1, 0.1, 0.12},
  ambient = {0.1, 0.1, 0.1},
}
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1.5, 1.5, 1.5} })
scene:add(c.object { mesh = c.mesh.plane { size = 3 }, material = c.material.diffuse { color = {0.8, 0.8, 0.8} } })
local quad = c.mesh.load(c.param("blend", false) and "../data/blend_quad.gltf" or "../data/cutout_quad.gltf")
if not c.param("mask", true) then
  quad.materials[1] = c.material.diffuse { color = {0.9, 0.47, 0.16} }
end
scene:add(c.object { mesh = quad, position = {0, 0.6, 0} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
