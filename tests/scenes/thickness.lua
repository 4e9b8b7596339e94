-- tests/data/thickness.gltf (make_thickness.py: a quad of glass with a
-- volume whose thicknessTexture is 0 on its left half and 1 on its right)
-- seen from above against a uniform grey environment, drawn by `shade`'s
-- one interface (which absorbs over the thickness; no refraction pass).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 2, 0.8}, target = {0, 0, 0}, fov = 40 },
  background = {0.5, 0.5, 0.5},
}
scene:add(c.object { mesh = c.mesh.load "../data/thickness.gltf", scale = {1.4, 1.4, 1.4} })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {64, 64} }
