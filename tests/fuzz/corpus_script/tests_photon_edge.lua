-- A glass sphere under a light from straight above, with a wall beside it
-- whose impostor rectangle the falling photons meet edge-on, and optionally
-- no receiver at all (--set receivers=false): zero photons land.
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1.5, 3}, target = {0, 0.3, 0} },
                        environment = c.cubemap "scenes/assets/env/room" }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3 }, position = {0, 0.8, 0},
                     material = c.material.glass { ior = c.param("ior", 1.5) } })
if c.param("receivers", true) then
  scene:add(c.object { mesh = c.mesh.box { size = {0.05, 1.0, 1.0} }, position = {0.7, 0.5, 0} })
  scene:add(c.object { mesh = c.mesh.plane { size = 3 } })
end
local g = c.graph()
g:add("photons", c.pass.photon_caustics { light = sun, buffer = 64, texture = c.param("texture", 128), k = c.param("k", 2) })
g:add("shade", c.pass.shade { caustics = "photons.irradiance" })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {64, 64} }
