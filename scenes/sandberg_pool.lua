-- Sandberg & Falemo, Fig. 4: an empty pool under a moving directional
-- light, a 64x64 water grid whose waves are driven by drops, caustics by
-- caustic volumes, the surface refraction-mapped (§3.5).
local c = require "caustica"
local pool = require "caustica.pool"

local grid = c.param("grid", 64)
local elevation = c.param("elevation", 60)     -- degrees; the light also turns around the pool
local underwater = c.param("underwater", false) -- a camera below the surface, looking up at a grazing angle

local scene = c.scene {
  camera = underwater and c.camera { eye = {-0.8, -0.45, 0.8}, target = {0.8, -0.1, -0.8}, fov = 60 }
                      or c.camera { eye = {0, 2.3, 2.0}, target = {0, -0.45, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.05, 0.06},
}
local sun = scene:add(c.light.directional { direction = {0.4, -1, 0.2}, intensity = {2.2, 2.1, 1.9} })
local water, g = pool.build(scene, { grid = grid, depth = 0.6, light = sun })
local drops = pool.drops(water, 2)

return {
  scene = scene, graph = g,
  update = function(t, dt)
    local e, a = math.rad(elevation), 0.3 * t
    sun.direction = { math.cos(e) * math.cos(a), -math.sin(e), math.cos(e) * math.sin(a) }
    drops(t, dt)
  end,
  frames = 150, fps = 30, size = {512, 512},
}
