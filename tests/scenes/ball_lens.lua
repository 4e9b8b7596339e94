-- A glass ball lens over a floor under a directional light (Issue 3's
-- closed-form checks): --set ior=, floor=<height of the floor below the
-- ball's centre>, hide=true, light=directional|point, elevation=degrees.
local c = require "caustica"
local ior = c.param("ior", 1.5)
local radius = c.param("radius", 0.5)
local floor_depth = c.param("floor", 1.0)      -- distance from the ball's centre down to the floor
local hide = c.param("hide", false)
local elevation = c.param("elevation", 90)
local size = c.param("size", 64)

local scene = c.scene {
  -- low and from the side, so the floor under the ball is seen past it
  camera = c.camera { eye = {0, -floor_depth + 0.5, 3}, target = {0, -floor_depth, 0}, fov = 20 },
  background = {0, 0, 0},
}
local e = math.rad(elevation)
scene:add(c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 40 }, position = {0, -floor_depth, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = radius, segments = 256 },
                                  material = c.material.glass { ior = ior } })
ball.visible = not hide
ball.cast_shadows = true
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {size, size} }
