-- Chaudhari 2008, Figs. 4.5-4.6: caustics through every interface onto the
-- floor, of a glass sphere (the thesis's check that the photon tracing is
-- right) or, with --set object=dragon, of the dragon; --set object=bunnies
-- for two bunnies. A directional light, photons from its view of the
-- depth layers (layered_caustics), refraction by layered_refraction.
local c = require "caustica"
local object = c.param("object", "sphere")
local scene = c.scene {
  camera = c.camera { eye = {0, 1.3, 2.2}, target = {0, 0, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.05, 0.05, 0.05},
}
local e = math.rad(c.param("elevation", 65))
local sun = scene:add(c.light.directional { direction = {0.4 * math.cos(e), -math.sin(e), -0.9 * math.cos(e)},
                                            intensity = {2.5, 2.4, 2.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.5, 0},
                     material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
local glass = c.material.glass { ior = c.param("ior", 1.5) }
if object == "sphere" then
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 128 }, material = glass, position = {0, 0.05, 0} })
elseif object == "dragon" then
  local m = c.mesh.load(c.param("model", "40k") == "800k" and(c.asset "dragon_800k.glb") or(c.asset "dragon_40k.glb"))
  scene:add(c.object { mesh = m, material = glass, position = {0, -0.5 - m.bounds[1][2], 0},
                       rotation = c.quat.axis_angle({0, 1, 0}, 0.4) })
else
  local m = c.mesh.load(c.asset "bunny_15k.glb")
  scene:add(c.object { mesh = m, material = glass, position = {-0.3, -0.5 - m.bounds[1][2], 0.1}, scale = {0.8, 0.8, 0.8} })
  scene:add(c.object { mesh = m, material = glass, position = {0.35, -0.5 - m.bounds[1][2] * 0.8, -0.3}, scale = {0.8, 0.8, 0.8},
                       rotation = c.quat.axis_angle({0, 1, 0}, 2.2) })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("caustics", c.pass.layered_caustics { light = sun, buffer = c.param("buffer", 512), layers = c.param("layers", 8) })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = 16 })
g:output(c.param("output", "glass.color"))
return { scene = scene, graph = g, size = {512, 512} }
