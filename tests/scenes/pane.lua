-- A pane of thin-walled glass (c.material.glass { thin = true }: glTF's
-- glass without KHR_materials_volume, issue 50) before a checkered wall
-- over a floor, a sun behind the camera. Light crosses the pane undeviated:
-- the wall is seen through it where it is, darkened by (1 - F) and the
-- tint, and the pane's shadow on the floor is (1 - F) x tint of the sun.
-- --set pane=false: no pane; fresnel=false: an ideal pane (F = 0), which
-- must vanish; tint=true: an orange pane; turn=A: the pane turned A
-- radians about the vertical (0: facing the camera); gltf=true: the pane
-- is tests/data/pane.gltf (made by make_pane.py: glTF's thin-walled glass,
-- no KHR_materials_volume, tinted pale blue by its baseColorTexture, a
-- crack along its diagonal cut out by alphaMode MASK), 1.2 across;
-- view=PASS: a glass ball (or, view=water_surface, a pool) behind the pane,
-- drawn over shade by that view technique (refraction, layered_refraction,
-- sliced_refraction), which must draw the pane over it; the sun from the
-- right; front=true: the ball before the pane instead, which it shows;
-- lookup=map: refraction's lookup of what lies behind the glass.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0.4, 3.2}, target = {0, 0, 0}, fov = 40 },
  background = {0.35, 0.4, 0.5},
  ambient = {0.15, 0.15, 0.15},
}
local view = c.param("view", "none")
-- with something behind the pane, the sun from the right, so that the
-- pane's shadow misses it: seen through the pane, it is dimmed by the pane
-- alone
local sun = scene:add(c.light.directional { direction = view == "none" and {-0.3, -0.6, -1} or {0.6, -0.8, -0.5},
                                            intensity = {2, 2, 2} })
local checker = c.texture.checker { size = 8, a = {0.9, 0.85, 0.8}, b = {0.15, 0.2, 0.3} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.5, -1.2},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = checker } })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.8, 0},
                     material = c.material.diffuse { color = {0.7, 0.7, 0.7} } })
if c.param("pane", true) then
  local turn = c.param("turn", 0.6)
  local rotation = c.quat.mul(c.quat.axis_angle({0, 1, 0}, turn), c.quat.axis_angle({1, 0, 0}, math.pi / 2))
  if c.param("gltf", false) then
    scene:add(c.object { mesh = c.mesh.load "../data/pane.gltf", position = {0, 0, 0.4}, rotation = rotation,
                         scale = {1.2, 1.2, 1.2} })
  else
    scene:add(c.object { mesh = c.mesh.plane { size = 1.2 }, position = {0, 0, 0.4}, rotation = rotation,
                         material = c.material.glass { thin = true, ior = 1.5,
                                                       fresnel = c.param("fresnel", true),
                                                       tint = c.param("tint", false) and {1, 0.6, 0.2} or nil } })
  end
end
local water
if view == "water_surface" then
  water = scene:add(c.water { size = {1.4, 0.9}, resolution = 64, depth = 0.45, position = {0, -0.35, -0.3} })
elseif view ~= "none" then
  -- front=true: the ball before the pane, which is seen through it
  local z = c.param("front", false) and 1.1 or -0.2
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, position = {0.05, -0.1, z},
                       material = c.material.glass { ior = 1.5 } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = view == "none" })
if view == "none" then
  g:output("shade.color")
elseif view == "water_surface" then
  g:add("view", c.pass.water_surface { water = water, color = "shade.color",
                                       depth = "shade.depth", position = "shade.position" })
  g:output("view.color")
else
  -- lookup=map: refraction finds what lies behind the glass in its distance map alone
  g:add("view", c.pass[view] { color = "shade.color", depth = "shade.depth", lookup = c.param("lookup", nil) })
  g:output("view.color")
end
return { scene = scene, graph = g, size = {128, 128} }
