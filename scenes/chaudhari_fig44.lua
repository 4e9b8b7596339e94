-- Chaudhari 2008, Fig. 4.4: glass bunnies absorbing 4.0 per unit length in
-- red and green (Beer-Lambert over the path inside, every interface), at
-- IOR 1.11, 1.15 and 1.25 from left to right. The thesis scales an optical
-- path length; here the length is geometric, as the reference's.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0.3, 2.6}, target = {0, 0.05, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
}
local bunny = c.mesh.load(c.asset "bunny_15k.glb")
local a = c.param("absorption", 4.0)
for i, ior in ipairs { 1.11, 1.15, 1.25 } do
  scene:add(c.object { mesh = bunny, material = c.material.glass { ior = ior, absorption = {a, a, 0} },
                       position = {-0.75 + 0.75 * (i - 1), 0, 0}, scale = {0.7, 0.7, 0.7},
                       rotation = c.quat.axis_angle({0, 1, 0}, 0.3) })
end
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = c.param("layers", 16) })
g:output("glass.color")
return { scene = scene, graph = g, size = {768, 384} }
