-- Refraction through every interface (layered_refraction) against the
-- two-interface pass (refraction) and the sliced object images (sliced_refraction), on the shapes Chaudhari's figures use:
-- --set object=sphere|torus|bunny|bunnies|dragon, method=layered|huqin|wyman|sliced,
-- ior=, absorption= (red and green, Fig. 4.4), layers=, voxels=, search=,
-- normals=mesh|gradient, depths=exact|voxel, room=true (a floor and a back
-- wall with boxes, looked up in screen space), hide=true (no refractor),
-- object=thin|inside_out, view=front|grazing|inside, interfaces=, output=glass.info,
-- shadows=false (no shadow map in the room).
local c = require "caustica"
local ior = c.param("ior", 1.5)
local method = c.param("method", "layered")
local object = c.param("object", "sphere")
local room = c.param("room", false)
local absorption = c.param("absorption", 0.0)
local views = {
  front = c.camera { eye = {0, 0.35, 2.4}, target = {0, 0.05, 0}, fov = 40 },
  grazing = c.camera { eye = {0, 0.05, 2.0}, target = {1.0, 0.0, 0.0}, fov = 60 },  -- the object at the image's edge
  inside = c.camera { eye = {0, 0, 0.2}, target = {0, 0, -1}, fov = 60, near = 0.01 }, -- the camera inside it
}
local scene = c.scene {
  camera = views[c.param("view", "front")],
  environment = c.cubemap "../../scenes/assets/env/room",
  ambient = {0.15, 0.15, 0.15},
}
local glass = c.material.glass { ior = ior, absorption = {absorption, absorption, 0} }
local objects = {}
local function add(mesh, position, scale, rotation)
  objects[#objects + 1] = scene:add(c.object { mesh = mesh, material = glass, position = position,
                                               scale = {scale, scale, scale}, rotation = rotation })
end
if object == "sphere" then
  add(c.mesh.sphere { radius = 0.6, segments = 96 }, {0, 0, 0}, 1)
elseif object == "torus" then
  add(c.mesh.torus { radius = 0.5, tube = 0.2, segments = 96, sides = 48 }, {0, 0, 0}, 1,
      c.quat.axis_angle({1, 0, 0}, 1.1))
elseif object == "bunny" then
  add(c.mesh.load "../../scenes/assets/bunny_15k.glb", {0, 0, 0}, 1.3)
elseif object == "bunnies" then   -- Fig. 4.3: two bunnies, one behind the other
  add(c.mesh.load "../../scenes/assets/bunny_15k.glb", {-0.25, 0, 0.25}, 1.0)
  add(c.mesh.load "../../scenes/assets/bunny_15k.glb", {0.3, 0.05, -0.35}, 1.0, c.quat.axis_angle({0, 1, 0}, 2.0))
elseif object == "dragon" then
  add(c.mesh.load "../../scenes/assets/dragon_40k.glb", {0, 0, 0}, 1.5, c.quat.axis_angle({0, 1, 0}, 0.6))
elseif object == "thin" then      -- a slab thinner than one voxel: its two faces share a slice
  add(c.mesh.box { size = {1.0, 0.8, 0.0005} }, {0, 0, 0}, 1, c.quat.axis_angle({0, 1, 0}, 0.4))
elseif object == "inside_out" then -- a deformer that mirrors the sphere: inward normals, reversed winding
  add(c.mesh.sphere { radius = 0.6, segments = 64 }, {0, 0, 0}, 1)
  objects[1].deform = c.deform.glsl [[ vec3 deform(vec3 p, float t) { return vec3(-p.x, p.y, p.z); } ]]
end
if c.param("hide", false) then
  for _, o in ipairs(objects) do o.visible = false end
end
local lamp
if room then
  lamp = scene:add(c.light.point { position = {1.5, 2.5, 2.0}, intensity = {5, 5, 5} })
  scene:add(c.object { mesh = c.mesh.plane { size = 10 }, position = {0, -0.65, 0},
                       material = c.material.diffuse { color = c.texture.checker { size = 20, a = {0.8, 0.8, 0.75}, b = {0.3, 0.3, 0.35} } } })
  scene:add(c.object { mesh = c.mesh.plane { size = 10 }, position = {0, 0, -2.0},
                       rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                       material = c.material.diffuse { color = {0.6, 0.5, 0.4} } })
  local colours = { {0.8, 0.2, 0.2}, {0.2, 0.7, 0.3}, {0.2, 0.3, 0.8}, {0.8, 0.7, 0.2} }
  for i, col in ipairs(colours) do
    scene:add(c.object { mesh = c.mesh.box { size = {0.35, 0.5, 0.35} }, position = {-1.2 + 0.8 * (i - 1), -0.4, -1.3},
                         material = c.material.diffuse { color = col } })
  end
end
local g = c.graph()
local shadow = nil
if lamp and c.param("shadows", true) then
  g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
  shadow = "shadow.depth"
end
if method == "sliced" then
  -- Iwasaki et al.'s sliced object images
  g:add("shade", c.pass.shade { specular = false, shadow = shadow })
  g:add("glass", c.pass.sliced_refraction { color = "shade.color", slices = c.param("slices", 6) })
elseif method == "layered" then
  g:add("shade", c.pass.shade { specular = false, shadow = shadow })
  g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = c.param("layers", 16),
                                             voxels = c.param("voxels", 256), search = c.param("search", 5),
                                             steps = c.param("steps", 8), normals = c.param("normals", "mesh"),
                                             depths = c.param("depths", "exact"),
                                             interfaces = c.param("interfaces", 0) })
else
  g:add("shade", c.pass.shade { shadow = shadow })
  g:add("glass", c.pass.refraction { method = method, color = "shade.color", internal = c.param("internal", 4) })
end
g:output(c.param("output", "glass.color"))
return { scene = scene, graph = g, size = {128, 128} }
