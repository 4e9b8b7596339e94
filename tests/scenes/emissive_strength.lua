-- The Khronos sample EmissiveStrengthTest: five cubes of emissive colour
-- (0.1, 0.5, 0.9), KHR_materials_emissive_strength 1, 2, 4, 8 and 16 from
-- left to right, before a backdrop, under a dim sun and sky (issue 50's
-- list of samples). Both renderers.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0, 20}, target = {0, 0, 0}, fov = 28, near = 1, far = 60 },
  background = {0.05, 0.05, 0.05},
  ambient = {0.1, 0.1, 0.1},
}
scene:add(c.light.directional { direction = {-0.3, -0.4, -1}, intensity = {0.5, 0.5, 0.5} })
scene:add(c.object { mesh = c.mesh.load(c.asset "khronos/EmissiveStrengthTest/EmissiveStrengthTest.glb") })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {160, 96} }
