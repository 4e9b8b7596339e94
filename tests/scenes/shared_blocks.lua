-- Three caustics techniques for one sun in one graph (issue 26): Sandberg &
-- Falemo's caustic volumes under the water, Liktor & Dachsbacher's beams
-- and Chaudhari's layered photons through the glass ball and the water.
-- The graph adds the building blocks they read: one receiver G-buffer for
-- all three, one set of the sun's depth layers for the beams and the
-- layered photons, and the camera's layers for layered_refraction. --set explicit=true names the blocks in the script
-- instead; --set buffer=N gives layered_caustics its own layer size (two
-- sets of layers, not shared).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 1.2, 2.2}, target = {0, -0.4, 0}, fov = 45 },
  background = {0.1, 0.1, 0.12},
}
local sun = scene:add(c.light.directional { direction = {0.3, -1, -0.2}, intensity = {0.8, 0.8, 0.8} })
scene:add(c.object { mesh = c.mesh.plane { size = 3 }, position = {0, -0.8, 0},
                     material = c.material.diffuse { color = {0.8, 0.8, 0.8} } })
scene:add(c.object { mesh = c.mesh.box { size = {0.3, 0.3, 0.3} }, position = {0.7, -0.65, -0.4},
                     material = c.material.diffuse { color = {0.7, 0.4, 0.3} } })
local water = scene:add(c.water { size = 3, resolution = 33, depth = 0.4, ior = 1.33 })
water:set_heights(function(x, z) return 0.02 * math.sin(6 * x) * math.cos(5 * z) end)
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.25, segments = 32 }, position = {-0.2, 0.35, 0},
                     material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
local buffer = c.param("buffer", 256)
if c.param("explicit", false) then
  g:add("recv", c.pass.receivers { position = true })
  g:add("sun_layers", c.pass.depth_layers { light = sun })
  g:add("volumes", c.pass.caustic_volumes { light = sun, water = water, receivers = "recv.normal" })
  g:add("beams", c.pass.beam_caustics { light = sun, receivers = "recv.normal", light_layers = "sun_layers.layers" })
  g:add("layered", c.pass.layered_caustics { light = sun, receivers = "recv.normal",
                                             light_layers = "sun_layers.layers" })
  g:add("camera_layers", c.pass.depth_layers { view = "camera", layers = 16 })
else
  g:add("volumes", c.pass.caustic_volumes { light = sun, water = water })
  g:add("beams", c.pass.beam_caustics { light = sun })
  g:add("layered", c.pass.layered_caustics { light = sun, buffer = buffer })
end
g:add("shade", c.pass.shade { caustics = { "volumes.irradiance", "beams.irradiance", "layered.irradiance" },
                              shadow = "shadow.depth", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color",
                                          camera_layers = c.param("explicit", false) and "camera_layers.layers" or nil })
g:output("glass.color")
return { scene = scene, graph = g, size = {128, 128} }
