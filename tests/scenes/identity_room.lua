-- Issue 8's identity in a room: a glass sphere in front of four coloured
-- boxes on a floor (size 10) before a back wall, a point light, no shadow
-- pass, Hu & Qin's refraction over shade. At ior = 1.0 the sphere must
-- vanish. --set ior=, sphere=false (the sphere-free render), mask=true (the
-- sphere's silhouette in white on black), lookup=distance|impostors,
-- correction=, impostor=, method=huqin|wyman, wall=false, checker=true (the
-- sphere 3.25 in front of a checkered wall, the issue's impostor case),
-- shadow=true (a shadow map for shade and the refraction's lookups: the
-- light as the reference computes it), fog=true (a homogeneous absorbing
-- medium over the room: the light reaches each surface attenuated),
-- output=exit (the refraction's exit directions)
local c = require "caustica"
local ior = c.param("ior", 1.0)
local mask = c.param("mask", false)
local checker = c.param("checker", false)
local scene = c.scene {
  camera = c.camera { eye = {0, 1.4, 4.2}, target = {0, 0.7, 0}, fov = 45 },
  background = {0, 0, 0},
  ambient = mask and {0, 0, 0} or {0.08, 0.08, 0.09},
}
if c.param("fog", false) then
  scene.medium = c.medium { sigma_s = {0.02, 0.02, 0.02}, sigma_a = {0.25, 0.2, 0.15}, box = {{-5, 0, -5}, {5, 5, 5}} }
end
local lamp = scene:add(c.light.point { position = {1.5, 3.5, 3.0}, intensity = mask and {0, 0, 0} or {14, 13, 12} })
local function diffuse(color)
  return c.material.diffuse { color = mask and {0, 0, 0} or color }
end
if checker then
  scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, 0.8, -3.25},
                       rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                       material = mask and diffuse({0, 0, 0})
                         or c.material.diffuse { color = c.texture.checker { size = 12 } } })
else
  scene:add(c.object { mesh = c.mesh.plane { size = 10 }, material = diffuse({0.7, 0.68, 0.62}) })
  if c.param("wall", true) then
    scene:add(c.object { mesh = c.mesh.plane { size = 10 }, position = {0, 2.5, -2.5},
                         rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2), material = diffuse({0.45, 0.55, 0.7}) })
  end
  local boxes = { {-1.3, -1.2, {0.8, 0.25, 0.2}}, {-0.4, -1.6, {0.25, 0.7, 0.3}}, {0.5, -1.3, {0.85, 0.75, 0.2}},
                  {1.4, -1.0, {0.3, 0.4, 0.85}} }
  for i, b in ipairs(boxes) do
    local h = 0.5 + 0.25 * i
    scene:add(c.object { mesh = c.mesh.box { size = {0.6, h, 0.6} }, position = {b[1], h / 2, b[2]},
                         material = diffuse(b[3]) })
  end
end
if c.param("sphere", true) then
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.55, segments = 96 }, position = {0, 0.8, 0.6},
                       material = mask and c.material.diffuse { color = {0, 0, 0}, emission = {1, 1, 1} }
                                   or c.material.glass { ior = ior, absorption = {0, 0, 0} } })
end
local g = c.graph()
local shadow = c.param("shadow", false) and not mask
if shadow then
  g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
end
g:add("shade", c.pass.shade { specular = c.param("specular", true), shadow = shadow and "shadow.depth" or nil })
if mask then
  g:output("shade.color")
else
  g:add("glass", c.pass.refraction { method = c.param("method", "huqin"), color = "shade.color", depth = "shade.depth",
                                      lookup = c.param("lookup", "scene"), correction = c.param("correction", 3),
                                      impostor = c.param("impostor", 256), iterations = c.param("iterations", 3), shadow = shadow and "shadow.depth" or nil })
  g:output("glass." .. c.param("output", "color")) -- output=exit: the direction each path leaves in
end
return { scene = scene, graph = g, size = {128, 128} }
