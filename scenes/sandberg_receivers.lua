-- Sandberg & Falemo, Fig. 3: caustics on complex receivers (the Stanford
-- bunny and the Happy Buddha) under a 128x128 water surface. With
-- --set receivers=N (1, 4, 16 ...) it places N bunnies instead, which is
-- how the bench checks that the caustics' cost does not grow with them.
local c = require "caustica"
local pool = require "caustica.pool"

local grid = c.param("grid", 128)
local receivers = c.param("receivers", 0)

local scene = c.scene {
  camera = c.camera { eye = {0, 1.7, 2.2}, target = {0, -0.4, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.05, 0.05, 0.06},
}
local sun = scene:add(c.light.directional { direction = {0.25, -1, -0.3}, intensity = {2.2, 2.1, 1.9} })
local water, g = pool.build(scene, { grid = grid, depth = 0.7, light = sun })
local marble = c.material.diffuse { color = {0.85, 0.83, 0.78} }
local bunny = c.mesh.load(c.asset "bunny_15k.glb")
if receivers > 0 then
  local side = math.ceil(math.sqrt(receivers))
  local scale = 1.4 / side
  for i = 0, receivers - 1 do
    local x, z = (i % side + 0.5) / side * 1.6 - 0.8, (math.floor(i / side) + 0.5) / side * 1.6 - 0.8
    scene:add(c.object { mesh = bunny, material = marble, scale = {scale, scale, scale},
                         position = {x, -0.7 - scale * bunny.bounds[1][2], z} })
  end
else
  scene:add(c.object { mesh = bunny, material = marble, scale = {0.6, 0.6, 0.6},
                       position = {-0.4, -0.7 - 0.6 * bunny.bounds[1][2], 0.1} })
  local buddha = c.mesh.load(c.asset "buddha_60k.glb")
  scene:add(c.object { mesh = buddha, material = marble, scale = {0.65, 0.65, 0.65},
                       position = {0.4, -0.7 - 0.65 * buddha.bounds[1][2], -0.1} })
end
local drops = pool.drops(water, 2, 0.3, 0.015, 3)

return { scene = scene, graph = g, update = drops, frames = 150, fps = 30, size = {512, 512} }
