-- Degenerate but legal cameras: --set view=eye_is_target|up_zero|up_parallel
local c = require "caustica"
local view = c.param("view", "eye_is_target")
local cameras = {
  eye_is_target = c.camera { eye = { 0, 1, 2 }, target = { 0, 1, 2 } },
  up_zero = c.camera { eye = { 0, 1, 2 }, target = { 0, 0, 0 }, up = { 0, 0, 0 } },
  up_parallel = c.camera { eye = { 0, 3, 0 }, target = { 0, 0, 0 }, up = { 0, 1, 0 } },
}
local scene = c.scene { camera = cameras[view], ambient = { 0.1, 0.1, 0.1 } }
local lamp = scene:add(c.light.point { position = { 1, 3, 1 }, intensity = { 5, 5, 5 } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5 }, position = { 0, 0.5, 0 },
                     material = c.material.glass { ior = 1.5 } })
scene:add(c.object { mesh = c.mesh.plane { size = 4 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 128 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:add("refraction", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("refraction.color")
return { scene = scene, graph = g, size = { 32, 32 } }
