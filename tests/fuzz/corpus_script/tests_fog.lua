-- A box of fog under a directional light, seen from the side: --set
-- density=homogeneous|linear, g=, ball=true (a glass ball above the fog
-- focusing a volume caustic into it), ior=, hide=true.
local c = require "caustica"
local mode = c.param("density", "homogeneous")
local g = c.param("g", 0.0)
local ball = c.param("ball", false)
local ior = c.param("ior", 1.5)
local size = c.param("size", 33)

local scene = c.scene {
  -- looking along +x through the fog box [-1,1] x [0,1] x [-1,1] at height 0.5
  camera = c.camera { eye = {-3, 0.5, 0}, target = {0, 0.5, 0}, fov = 30 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
local density = 1.0
if mode == "linear" then
  density = function(x, y, z) return 0.5 + 1.5 * y end   -- trilinear grids hold a linear function exactly
end
scene.medium = c.medium { sigma_s = {0.5, 0.4, 0.3}, sigma_a = {0.1, 0.2, 0.3}, g = g, density = density,
                          resolution = {4, 9, 4}, box = {{-1, 0, -1}, {1, 1, 1}} }
if ball then
  local sphere = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4, segments = 128 }, position = {0, 1.6, 0},
                                      material = c.material.glass { ior = ior } })
  sphere.visible = not c.param("hide", false)
end
local gr = c.graph()
gr:add("shade", c.pass.shade {})
gr:output("shade.color")
return { scene = scene, graph = gr, size = {size, size} }
