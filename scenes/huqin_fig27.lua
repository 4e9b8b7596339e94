-- Hu & Qin Fig. 27: caustics on two objects from two lights: a glass sphere
-- over a floor and a box, lit by two point lights, one photon pass each.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0.3, 1.5, 2.6}, target = {0, 0.3, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.035},
}
local warm = scene:add(c.light.point { position = {-1.0, 2.2, 0.4}, intensity = {6, 4.5, 3} })
local cool = scene:add(c.light.point { position = {1.1, 2.0, -0.2}, intensity = {3, 4.5, 6} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.75, 0.75} } })
scene:add(c.object { mesh = c.mesh.box { size = {0.5, 0.25, 0.5} }, position = {0.35, 0.125, -0.1},
                     material = c.material.diffuse { color = {0.6, 0.7, 0.8} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.25, segments = 64 }, position = {0, 0.75, 0},
                     material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow_warm", c.pass.shadow_map { light = warm, size = 1024 })
g:add("shadow_cool", c.pass.shadow_map { light = cool, size = 1024 })
g:add("photons_warm", c.pass.photon_caustics { light = warm, buffer = 256, texture = 512 })
g:add("photons_cool", c.pass.photon_caustics { light = cool, buffer = 256, texture = 512 })
g:add("shade", c.pass.shade { shadow = {"shadow_warm.depth", "shadow_cool.depth"},
                              caustics = {"photons_warm.irradiance", "photons_cool.irradiance"} })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
