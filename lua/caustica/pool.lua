-- A tiled pool with a simulated water surface, as in Sandberg & Falemo's
-- figures: floor and four walls around a basin `depth` deep, size x size
-- or size[1] (x) by size[2] (z),
-- the water's mean level at y = 0, drops at regular times, and the passes
-- of §3.5 (shadow map, caustic volumes, shading, the surface).
local c = require "caustica"

local pool = {}

--- Adds the pool to `scene`; returns the water object and a graph.
--- opts: size (a number or {x, z}), depth, grid (vertices along the longer
--- side), light, attenuation, damping, wave_speed, tiles (material)
---
--- The basin both renderers see: a floor plane exactly under the water (the
--- same extent, `depth` below its mean level) and four walls 0.1 thick whose
--- inner faces stand on the water's edges and rise 0.075 above it, so that
--- every refracted ray ends on the floor or a wall, never in the void.
function pool.build(scene, opts)
  local size, depth = opts.size or 2, opts.depth or 0.6
  local sx, sz = size, size
  if type(size) == "table" then sx, sz = size[1], size[2] end
  local tiles = opts.tiles or c.material.diffuse { color = { 0.55, 0.72, 0.78 } }
  scene:add(c.object { mesh = c.mesh.plane { size = { sx, sz } }, position = { 0, -depth, 0 }, material = tiles })
  local hx, hz, t = sx / 2 + 0.05, sz / 2 + 0.05, 0.1
  for _, w in ipairs { { hx, 0, t, sz + 2 * t }, { -hx, 0, t, sz + 2 * t }, { 0, hz, sx + 2 * t, t }, { 0, -hz, sx + 2 * t, t } } do
    scene:add(c.object { mesh = c.mesh.box { size = { w[3], depth + 0.15, w[4] } }, material = tiles,
                         position = { w[1], -depth / 2 + 0.075, w[2] } })
  end
  local water = scene:add(c.water { size = { sx, sz }, resolution = opts.grid or 64, depth = depth,
                                    attenuation = opts.attenuation or { 0.35, 0.12, 0.08 },
                                    damping = opts.damping or 0.3, wave_speed = opts.wave_speed or 0.6 })
  local g = c.graph()
  g:add("shadow", c.pass.shadow_map { light = opts.light, size = 1024 })
  g:add("cv", c.pass.caustic_volumes { light = opts.light, water = water })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "cv.irradiance", specular = false })
  g:add("surface", c.pass.water_surface { water = water, color = "shade.color", depth = "shade.depth",
                                          position = "shade.position" })
  g:output("surface.color")
  return water, g
end

--- An update step that drops a bump every `every` seconds at a pseudo-random
--- place (the same places whichever verb renders) and advances the water.
function pool.drops(water, size, every, strength, seed)
  local state = seed or 7
  local function random()
    state = (state * 1103515245 + 12345) % 2147483648
    return state / 2147483648
  end
  local next_drop = 0
  return function(t, dt)
    if t >= next_drop then
      local rx, rz = 0.8 * size / 2, 0.8 * size / 2
      if type(size) == "table" then rx, rz = 0.8 * size[1] / 2, 0.8 * size[2] / 2 end
      water:drop(2 * rx * random() - rx, 2 * rz * random() - rz, 0.12 + 0.1 * random(), strength or 0.02)
      next_drop = next_drop + (every or 0.4)
    end
    water:step(dt)
  end
end

return pool
