-- A flat water surface over a floor under a directional light, seen by a
-- camera under water looking straight down (Issue 3's closed form):
-- --set depth=, elevation=degrees, ior=, camera_height=
local c = require "caustica"
local depth = c.param("depth", 0.5)
local elevation = c.param("elevation", 60)
local ior = c.param("ior", 1.33)
local camera_height = c.param("camera_height", 0.3)    -- above the floor, under the surface
local size = c.param("size", 64)
local e = math.rad(elevation)

local scene = c.scene {
  camera = c.camera { eye = {0, -depth + camera_height, 0}, target = {0, -depth, 0}, up = {0, 0, -1}, fov = 40 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 3 }, position = {0, -depth, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.object { mesh = c.mesh.grid { size = 3, resolution = 8 },
                     material = c.material.water { ior = ior, absorption = {0.2, 0.5, 1.0} } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {size, size} }
