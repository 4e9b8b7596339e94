-- Sandberg & Falemo, Fig. 4: an empty pool under a moving directional
-- light, a 64x64 water grid whose waves are driven by drops, caustics by
-- caustic volumes, the surface refraction-mapped (§3.5).
local c = require "caustica"

local grid = c.param("grid", 64)
local depth = c.param("depth", 0.6)
local elevation = c.param("elevation", 60)     -- degrees; the light also turns around the pool
local drops = c.param("drops", true)
local underwater = c.param("underwater", false)   -- a camera below the surface, looking up at a grazing angle

local scene = c.scene {
  camera = underwater and c.camera { eye = {-0.8, -0.45, 0.8}, target = {0.8, -0.1, -0.8}, fov = 60 }
                      or c.camera { eye = {0, 2.3, 2.0}, target = {0, -0.45, 0}, fov = 45 },
  environment = c.cubemap "assets/env/room",
  ambient = {0.04, 0.05, 0.06},
}
local sun = scene:add(c.light.directional { direction = {0.4, -1, 0.2}, intensity = {2.2, 2.1, 1.9} })
local tiles = c.material.diffuse { color = {0.55, 0.72, 0.78} }
scene:add(c.object { mesh = c.mesh.plane { size = 2 }, position = {0, -depth, 0}, material = tiles })
for _, w in ipairs { {1.05, 0, 0.1, 2.2}, {-1.05, 0, 0.1, 2.2}, {0, 1.05, 2.2, 0.1}, {0, -1.05, 2.2, 0.1} } do
  scene:add(c.object { mesh = c.mesh.box { size = {w[3], depth + 0.15, w[4]} }, material = tiles,
                       position = {w[1], -depth / 2 + 0.075, w[2]} })
end
local water = scene:add(c.water { size = 2, resolution = grid, depth = depth, attenuation = {0.35, 0.12, 0.08},
                                  damping = 0.3, wave_speed = 0.6 })

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("cv", c.pass.caustic_volumes { light = sun, water = water })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "cv.irradiance", specular = false })
g:add("surface", c.pass.water_surface { water = water, color = "shade.color", depth = "shade.depth",
                                        position = "shade.position" })
g:output("surface.color")

math.randomseed(7) -- drops at the same places whichever verb renders
local next_drop = 0
return {
  scene = scene, graph = g,
  update = function(t, dt)
    local e, a = math.rad(elevation), 0.3 * t
    sun.direction = { math.cos(e) * math.cos(a), -math.sin(e), math.cos(e) * math.sin(a) }
    if drops and t >= next_drop then
      water:drop(1.6 * math.random() - 0.8, 1.6 * math.random() - 0.8, 0.12 + 0.1 * math.random(), 0.02)
      next_drop = next_drop + 0.4
    end
    water:step(dt)
  end,
  frames = 150, fps = 30, size = {512, 512},
}
