-- A glass sphere in front of the environment: --set ior=..., hide=true.
local c = require "caustica"
local ior = c.param("ior", 1.5)
local hide = c.param("hide", false)
local scene = c.scene { camera = c.camera { eye = {0, 0.3, 2.5}, target = {0, 0, 0}, fov = 40 },
                        environment = c.cubemap "scenes/assets/env/room" }
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.6, segments = 64 },
                                  material = c.material.glass { ior = ior } })
ball.visible = not hide
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {64, 64} }
