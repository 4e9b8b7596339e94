-- The Khronos sample VertexColorTest (issue 50's list): COLOR_0 multiplies
-- the base colour. Its top row's checkmarks are multiplied by red, green and
-- blue vertex colours, which hide the crosses drawn in the other channels;
-- the bottom row (white vertex colours) looks the same either way. Seen
-- face-on under a sky (and a weak sun), both renderers.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0, 3.2}, target = {0, 0, 0}, fov = 40, near = 0.5, far = 10 },
  background = {0.2, 0.2, 0.2},
  ambient = {0.8, 0.8, 0.8},
}
scene:add(c.light.directional { direction = {0, 0, -1}, intensity = {0.5, 0.5, 0.5} })
local mesh = c.mesh.load(c.asset "khronos/VertexColorTest/VertexColorTest.glb")
scene:add(c.object { mesh = mesh })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {192, 192} }
