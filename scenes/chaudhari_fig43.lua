-- Chaudhari 2008, Fig. 4.3: two glass bunnies (IOR 1.2), one behind the
-- other, refracted through every interface of both: each keeps its own
-- material (the layers record which object they belong to). A room around
-- them (floor and back wall, seen through the glass in screen space).
-- --set method=huqin for the two-interface pass.
local c = require "caustica"
local method = c.param("method", "layered")
local scene = c.scene {
  camera = c.camera { eye = {0.3, 0.5, 2.3}, target = {0, 0.1, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.1, 0.1, 0.1},
}
local lamp = scene:add(c.light.point { position = {1.5, 2.5, 2.0}, intensity = {6, 6, 6} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, -0.45, 0},
                     material = c.material.diffuse { color = c.texture.checker { size = 16, a = {0.8, 0.8, 0.75},
                                                                                  b = {0.35, 0.35, 0.4} } } })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, 0, -1.8},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = {0.55, 0.5, 0.45} } })
local bunny = c.mesh.load(c.asset "bunny_15k.glb")
local ior = c.param("ior", 1.2)
scene:add(c.object { mesh = bunny, material = c.material.glass { ior = ior },
                     position = {-0.3, -0.45 - bunny.bounds[1][2], 0.25} })
scene:add(c.object { mesh = bunny, material = c.material.glass { ior = ior, absorption = {0.0, 0.3, 0.6} },
                     position = {0.35, -0.45 - bunny.bounds[1][2], -0.4}, rotation = c.quat.axis_angle({0, 1, 0}, 2.0) })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
if method == "layered" then
  g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = c.param("layers", 16) })
else
  g:add("shade", c.pass.shade { shadow = "shadow.depth" })
  g:add("glass", c.pass.refraction { method = method, color = "shade.color" })
end
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
