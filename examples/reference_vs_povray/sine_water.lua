-- Clear water (n = 1.33), 0.5 deep, its surface ridged along x,
-- y = A cos(2 pi x / L) with A = 0.06, L = 0.5: under a vertical sun each
-- crest focuses at about 0.42 below it, above the floor, so the floor sees
-- two caustic folds per crest (where the map from the surface to the floor
-- folds over) with the bright band between them (folds at x = +-0.00939).
-- Camera under water as in flat_water.lua, shifted by half a pixel (0.000853)
-- so that the folds fall on pixel edges, not on the pixel centres where
-- the irradiance is sampled (it is infinite on a fold). Twin of
-- sine_water.pov.
local c = require "caustica"
local A, L = 0.06, 0.5
local scene = c.scene {
  camera = c.camera { eye = {0.000853, -0.2, 0}, target = {0.000853, -0.5, 0}, up = {0, 0, -1}, fov = 40 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.5, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
local water = scene:add(c.water { size = 3, resolution = 769, depth = 0.5, ior = 1.33, attenuation = {0, 0, 0} })
water:set_heights(function(x, z) return A * math.cos(2 * math.pi * x / L) end)
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
