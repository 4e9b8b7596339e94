-- A normal map on solid glass and on a mirror (issue 50: glTF's
-- normalTexture on glass with a volume and on metals drawn as mirrors):
-- a slab of glass (or, --set kind=mirror, a mirror tilted to show the
-- floor's checker) with a normal map of ridges (tests/data/normal_ridges.png)
-- before a checkered wall, drawn by `refraction`, which maps it as the
-- reference does. --set normal_map=false: the same without the map;
-- flat=true: a flat map (tests/data/normal_flat.png), which must change
-- nothing but its 8-bit rounding.
local c = require "caustica"
local kind = c.param("kind", "glass")
local scene = c.scene {
  camera = c.camera { eye = {0, 0.3, 2.6}, target = {0, 0, 0}, fov = 38 },
  background = {0.35, 0.4, 0.5},
  -- the mirror reflects the sky: a room's cube map, so that its ridges show
  environment = kind == "mirror" and c.cubemap(c.asset "env/room") or nil,
  ambient = {0.2, 0.2, 0.2},
}
local sun = scene:add(c.light.directional { direction = {-0.3, -0.7, -0.6}, intensity = {2, 2, 2} })
local checker = c.texture.checker { size = 10, a = {0.9, 0.85, 0.8}, b = {0.15, 0.2, 0.3} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.4, -1.0},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = checker } })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.7, 0},
                     material = c.material.diffuse { color = checker } })
local ridges = c.param("normal_map", true) and
               c.texture { file = c.param("flat", false) and "../data/normal_flat.png" or "../data/normal_ridges.png",
                           filter = "linear" } or nil
if kind == "mirror" then
  scene:add(c.object { mesh = c.mesh.plane { size = 1.1 }, position = {0, -0.05, 0.1},
                       rotation = c.quat.axis_angle({1, 0, 0}, 1.1),
                       material = c.material.mirror { color = {0.9, 0.9, 0.9}, normal = ridges } })
else
  scene:add(c.object { mesh = c.mesh.box { size = {1.1, 0.9, 0.12} }, position = {0, 0, 0.3},
                       material = c.material.glass { ior = 1.5, normal = ridges } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {128, 128} }
