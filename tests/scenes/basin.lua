-- Rectangular water in a basin: c.water { size = {3, 1.5} } in the pool
-- module's basin (floor and walls fitted to the water's extent), a
-- sinusoidal surface set by set_heights (deterministic, no simulation), a
-- directional light; caustic volumes on the floor and the surface
-- refraction-mapped. --set ripple=0 for a flat surface.
local c = require "caustica"
local pool = require "caustica.pool"
local scene = c.scene {
  camera = c.camera { eye = {0, 2.6, 2.2}, target = {0, -0.4, 0}, fov = 50 },
  background = {0.3, 0.35, 0.4},
  ambient = {0.03, 0.03, 0.03},
}
local sun = scene:add(c.light.directional { direction = {0.3, -1, 0.15}, intensity = {2, 2, 2} })
local water, g = pool.build(scene, { size = {3, 1.5}, depth = 0.6, grid = c.param("grid", 97), light = sun,
                                     attenuation = {0.3, 0.1, 0.05} })
local ripple = c.param("ripple", 0.012)
water:set_heights(function(x, z)
  return ripple * math.sin(2 * math.pi * x / 0.5) * math.cos(2 * math.pi * z / 0.7)
end)
return { scene = scene, graph = g, size = {128, 128} }
