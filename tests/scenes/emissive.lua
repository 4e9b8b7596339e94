-- Emissive surfaces, no lights: a glowing panel (c.material.emissive, or
-- the glTF quad tests/data/emissive_quad.gltf with emissiveFactor x
-- KHR_materials_emissive_strength = (4, 2, 1) when --set gltf=true), seen
-- directly and through a glass ball in front of it (--set ball=false to
-- leave the ball out).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0, 3}, target = {0, 0, 0}, fov = 40 },
  background = {0, 0, 0},
}
if c.param("gltf", false) then
  -- the unit quad (0..1 in x and y, facing +z) scaled up behind the ball
  scene:add(c.object { mesh = c.mesh.load "../data/emissive_quad.gltf", position = {-1.5, -1.5, -1}, scale = {3, 3, 3} })
else
  scene:add(c.object { mesh = c.mesh.plane { size = 3 }, position = {0, 0, -1},
                       rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                       material = c.material.emissive { color = {1, 0.5, 0.25}, strength = 2 } })
end
-- a dark diffuse stripe on the panel, so that refraction shows structure
scene:add(c.object { mesh = c.mesh.box { size = {0.3, 3, 0.05} }, position = {0.4, 0, -0.95},
                     material = c.material.diffuse { color = {0.5, 0.5, 0.5} } })
if c.param("ball", true) then
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5, segments = 96 }, material = c.material.glass { ior = 1.5 } })
end
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {64, 64} }
