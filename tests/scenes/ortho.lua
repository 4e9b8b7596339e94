-- An orthographic camera (c.camera { ortho = { width } }): the floor under
-- a glass ball lens seen straight down, each pixel the same size on the
-- floor -- the natural view of an irradiance map. --set ortho=false for a
-- perspective camera, shape=ball|cube, near=, far=.
local c = require "caustica"
local ortho = c.param("ortho", true)
local size = c.param("size", 64)
local scene = c.scene {
  camera = c.camera { eye = {0, c.param("height", 3), 0}, target = {0, 0, 0}, up = {0, 0, -1}, fov = 30,
                      near = c.param("near", 0.05), far = c.param("far", 100),
                      ortho = ortho and { width = c.param("width", 2.0) } or false },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = {0.3, -1, 0.2}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 10 }, material = c.material.diffuse { color = {0.9, 0.9, 0.9} } })
if c.param("shape", "ball") == "cube" then
  scene:add(c.object { mesh = c.mesh.box { size = {0.6, 0.6, 0.6} }, position = {0.3, 0.8, 0},
                       material = c.material.diffuse { color = {0.8, 0.3, 0.2} } })
else
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4, segments = 96 }, position = {0, 0.9, 0},
                       material = c.material.glass { ior = 1.5 } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("photons", c.pass.photon_caustics { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
g:add("glass", c.pass.refraction { method = "huqin", color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {size, size} }
