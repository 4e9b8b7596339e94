-- A glass ball lens (R = 0.5, n = 1.5) focusing a vertical sun onto a floor
-- at its paraxial focus, f = nR / (2(n - 1)) = 0.75 below its centre (or
-- at --set depth=D), seen from 0.2 (--set height=H) above the floor looking
-- straight down (the view lies inside the ball's shadow: everything in it
-- is caustic). Twin of ball_lens.pov (Declare=Depth=D Declare=Height=H).
local c = require "caustica"
local floor_y = -c.param("depth", 0.75)
local height = c.param("height", 0.2)
local scene = c.scene {
  camera = c.camera { eye = {0, floor_y + height, 0}, target = {0, floor_y, 0}, up = {0, 0, -1}, fov = 60 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 40 }, position = {0, floor_y, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5, segments = 512 }, material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
