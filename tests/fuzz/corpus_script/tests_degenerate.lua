-- Degenerate input: zero-area triangles (the sphere's poles, a flattened
-- box), a camera at a grazing angle to the floor, and with --set
-- extreme=true huge morph weights and a deformer that returns NaN.
local c = require "caustica"
local extreme = c.param("extreme", false)
local scene = c.scene { camera = c.camera { eye = {0, 0.001, 4}, target = {0, 0, 0}, fov = 60, near = 1e-4 } }
local lamp = scene:add(c.light.point { position = {0, 0.5, 1}, intensity = {4, 4, 4} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 } })
scene:add(c.object { mesh = c.mesh.box { size = {1, 1, 1} }, scale = {1, 0, 1}, position = {0.5, 0.2, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3, segments = 3 }, position = {-0.5, 0.3, 0} })
local dino = scene:add(c.object { mesh = c.mesh.load "scenes/assets/dinosaur_morph.glb", position = {0, 0.3, 1} })
if extreme then
  dino.morph_weights = { 1e6 }
  dino.deform = c.deform.glsl "vec3 deform(vec3 p, float t) { return p / (p.x - p.x); }"
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 256 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
return { scene = scene, graph = g, size = {64, 64} }
