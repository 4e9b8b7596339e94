-- Sandberg & Falemo, Fig. 7: pots on the bottom of a pool under a 128x128
-- water surface; the caustics fall on them as on the floor.
local c = require "caustica"
local pool = require "caustica.pool"

local grid = c.param("grid", 128)

local scene = c.scene {
  camera = c.camera { eye = {0.3, 1.9, 2.1}, target = {0, -0.5, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.05, 0.06},
}
local sun = scene:add(c.light.directional { direction = {-0.3, -1, -0.25}, intensity = {2.2, 2.1, 1.9} })
local water, g = pool.build(scene, { grid = grid, depth = 0.6, light = sun })
local pot = c.mesh.load(c.asset "teapot.glb")
local clay = c.material.diffuse { color = {0.75, 0.45, 0.3} }
for i, p in ipairs { {-0.45, -0.3}, {0.35, -0.4}, {0.05, 0.35} } do
  scene:add(c.object { mesh = pot, material = clay, scale = {0.5, 0.5, 0.5},
                       position = {p[1], -0.6 - 0.5 * pot.bounds[1][2], p[2]},
                       rotation = c.quat.axis_angle({0, 1, 0}, 1.3 * i) })
end
local drops = pool.drops(water, 2, 0.35, 0.015, 11)

return { scene = scene, graph = g, update = drops, frames = 150, fps = 30, size = {512, 512} }
