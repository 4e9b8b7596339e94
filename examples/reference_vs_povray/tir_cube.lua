-- A unit cube of IOR 2.42 (diamond) floating 0.5 above a floor, lit by a
-- sun 30 degrees from vertical in the x-y plane: light entering the top
-- face meets the +x face beyond the critical angle (24.4 degrees) and is
-- totally reflected; the floor beside and under the cube gets the folded
-- beams. Seen from 0.4 above the floor, fov 90. Twin of tir_cube.pov.
local c = require "caustica"
local s = math.rad(30)
local scene = c.scene {
  camera = c.camera { eye = {0.25, -0.6, 0}, target = {0.25, -1.0, 0}, up = {0, 0, -1}, fov = 90 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {math.sin(s), -math.cos(s), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 40 }, position = {0, -1.0, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.object { mesh = c.mesh.box { size = {1, 1, 1} }, material = c.material.glass { ior = 2.42 } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
