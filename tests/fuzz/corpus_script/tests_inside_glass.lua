-- A camera inside a glass box looking out at a grazing angle: most rays
-- meet the walls beyond the critical angle and reflect inside.
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0, 0}, target = {1, 0.1, 0.2}, fov = 90 },
                        environment = c.cubemap "scenes/assets/env/room" }
scene:add(c.light.point { position = {0, 3, 0}, intensity = {5, 5, 5} })
scene:add(c.object { mesh = c.mesh.box { size = {2, 2, 2} }, material = c.material.glass { ior = 1.5, absorption = {0.1, 0.1, 0.1} } })
scene:add(c.object { mesh = c.mesh.plane { size = 10 }, position = {0, -2, 0} })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32} }
