-- Record an animation: a sphere bouncing under a spot light.
--   caustica record examples/record_animation.lua -o out/bounce --size 256x256
-- writes out/bounce/frame_0000.png ... frame_0059.png (ffmpeg -i out/bounce/frame_%04d.png bounce.mp4).
local c = require "caustica"

local scene = c.scene { camera = c.camera { eye = {0, 1.5, 4}, target = {0, 0.6, 0} } }
local spot = scene:add(c.light.spot { position = {0, 4, 1}, direction = {0, -4, -1}, angle = 35,
                                      intensity = {30, 28, 25} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 } })
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 },
                                  material = c.material.diffuse { color = {0.9, 0.3, 0.2} } })

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = spot, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")

return {
  scene = scene, graph = g,
  update = function(t, dt)
    ball.position = { 0, 0.4 + 1.2 * math.abs(math.sin(math.pi * t)), 0 }
  end,
  frames = 60, fps = 30, size = {512, 512},
}
