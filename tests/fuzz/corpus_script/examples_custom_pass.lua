-- Write your own passes: a fullscreen shader (vignette.frag) and a pass in Lua.
--   caustica render examples/custom_pass.lua -o out/custom.png
local c = require "caustica"

local strength = c.param("strength", 0.8)

local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0.3, 0} },
                        environment = c.cubemap "scenes/assets/env/room" }
local lamp = scene:add(c.light.point { position = {1, 3, 2}, intensity = {10, 10, 10} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, position = {0, 0.4, 0},
                     material = c.material.mirror {} })

local g = c.graph()
-- A pass written in Lua: run(ctx) clears outputs and runs fullscreen shaders.
g:add("tint", c.pass.custom {
  outputs = { color = "rgba16f" },
  run = function(ctx) ctx:clear("color", { 1.0, 0.95, 0.85, 1 }) end,
})
g:add("shadow", c.pass.shadow_map { light = lamp, size = 512 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
-- A fullscreen GLSL pass: samplers are named after the inputs, uniforms set by name.
g:add("vignette", c.pass.fullscreen {
  shader = "vignette.frag",
  inputs = { image = "shade.color", tint = "tint.color" },
  uniforms = { strength = strength },
})
g:output("vignette.color")

return { scene = scene, graph = g, size = {512, 512} }
