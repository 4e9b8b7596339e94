-- Flat clear water (n = 1.33), 0.5 deep, under a sun at elevation 60
-- degrees; the camera is under water, 0.3 above the floor, looking
-- straight down. The floor's irradiance is E cos(30) T(30) everywhere.
-- Twin of flat_water.pov (which fills the water as a box).
local c = require "caustica"
local e = math.rad(60)
local scene = c.scene {
  camera = c.camera { eye = {0, -0.2, 0}, target = {0, -0.5, 0}, up = {0, 0, -1}, fov = 40 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.5, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.water { size = 6, resolution = 9, depth = 0.5, ior = 1.33, attenuation = {0, 0, 0} })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
