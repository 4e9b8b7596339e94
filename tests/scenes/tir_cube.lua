-- A cube of IOR 2.42 (critical angle 24.4 degrees) turned 30 degrees and
-- seen from above at an angle, in the room environment: most of the rays
-- that enter through its faces meet total internal reflection at the back.
-- --set output=color|tir|exit picks the refraction pass's output; ior=;
-- method=layered (layered_refraction; outputs color|info); internal= (either pass's).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {1.6, 1.4, 2.4}, target = {0, 0, 0}, fov = 35 },
  environment = c.cubemap "../../scenes/assets/env/room",
}
scene:add(c.object { mesh = c.mesh.box { size = {1, 1, 1} },
                     rotation = c.quat.axis_angle({0, 1, 0}, math.rad(30)),
                     material = c.material.glass { ior = c.param("ior", 2.42), fresnel = c.param("fresnel", true) } })
local g = c.graph()
if c.param("method", "huqin") == "layered" then
  -- every interface (layered_refraction): its debug output is `info`
  g:add("shade", c.pass.shade { specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color", internal = c.param("internal", 2) })
else
  g:add("shade", c.pass.shade {})
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth", internal = c.param("internal", 4) })
end
g:output("glass." .. c.param("output", "color"))
return { scene = scene, graph = g, size = {64, 64} }
