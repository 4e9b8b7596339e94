-- An environment from float data (--set env=PATH: an equirectangular .hdr
-- or .pfm, or a folder of px/nx/py/ny/pz/nz faces in .pfm, .hdr or .png),
-- seen directly by a camera looking along --set look=up|down|front|right,
-- and through a glass ball (--set ball=true).
local c = require "caustica"
local look = c.param("look", "front")
local dirs = { up = {0, 1, 0}, down = {0, -1, 0}, front = {0, 0, -1}, right = {1, 0, 0} }
local d = dirs[look]
local scene = c.scene {
  camera = c.camera { eye = {0, 0, 0}, target = d, up = (look == "up" or look == "down") and {0, 0, -1} or {0, 1, 0},
                      fov = 10 },
  environment = c.cubemap(c.param("env", "../../scenes/assets/env/room")),
}
if c.param("ball", false) then
  scene.camera = c.camera { eye = {0, 0, 3}, target = {0, 0, 0}, fov = 40 }
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.7, segments = 96 }, material = c.material.glass { ior = 1.5 } })
end
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {32, 32} }
