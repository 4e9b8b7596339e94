-- Hu & Qin Fig. 24: one scene, the same ladder of features (the sphere's
-- IOR is 1.15): --set stage=
--   plain  shading only (the baseline frame time)
--   a      refraction of the environment map
--   b      uncorrected refraction of nearby geometry
--   c      corrected refraction of nearby geometry
--   d      refraction and caustics, photon buffer 64^2
--   e      refraction and caustics, photon buffer 128^2
--   f      reflection, refraction and caustics, photon buffer 128^2
--   g      recursive reflection and refraction: a mirror teapot beside the
--          sphere, each seeing the other (two levels)
local c = require "caustica"
local stage = c.param("stage", "f")

local scene = c.scene {
  camera = c.camera { eye = {0, 1.3, 2.6}, target = {0, 0.35, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.045},
}
local lamp = scene:add(c.light.point { position = {0.9, 2.4, 1.0}, intensity = {7, 6.8, 6.4} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
local buddha = c.mesh.load(c.asset "buddha_60k.glb")
scene:add(c.object { mesh = buddha, position = {-0.1, -0.8 * buddha.bounds[1][2], -0.8}, scale = {0.8, 0.8, 0.8},
                     material = c.material.diffuse { color = {0.85, 0.7, 0.4} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, position = {0.15, 0.5, 0.2},
                     material = c.material.glass { ior = 1.15 } })
if stage == "g" then
  local teapot = c.mesh.load(c.asset "teapot.glb")
  scene:add(c.object { mesh = teapot, position = {-0.75, -0.6 * teapot.bounds[1][2], 0.3}, scale = {0.6, 0.6, 0.6},
                       rotation = c.quat.axis_angle({0, 1, 0}, 0.8), material = c.material.mirror { color = {0.9, 0.9, 0.95} } })
end

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
local caustics = stage == "d" or stage == "e" or stage == "f" or stage == "g"
if caustics then
  g:add("photons", c.pass.photon_caustics { light = lamp, buffer = stage == "d" and 64 or 128, texture = 512 })
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics and "photons.irradiance" or nil })
if stage == "plain" then
  g:output("shade.color")
else
  if not ({ a = 1, b = 1, c = 1, d = 1, e = 1, f = 1, g = 1 })[stage] then
    error("stage must be plain or a..g, got '" .. tostring(stage) .. "'")
  end
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth", nearby = stage ~= "a",
                                     correction = stage == "b" and 0 or 3, reflection = stage == "f" or stage == "g",
                                     recursion = stage == "g" and c.param("recursion", 2) or 0,
                                     -- the paper's impostors (b, c: Fig. 16's correction); --set lookup=scene: the pass's default
                                     lookup = c.param("lookup", "impostors") })
  g:output("glass.color")
end
-- The lamp drifts a little every frame so that nothing is reused between
-- frames (§4 would otherwise keep the shadow map and the photon buffer),
-- which is what the paper's frame rates measure.
return {
  scene = scene, graph = g,
  update = function(t, dt)
    lamp.position = { 0.9 + 0.05 * math.cos(2 * t), 2.4, 1.0 + 0.05 * math.sin(2 * t) }
  end,
  frames = 60, fps = 30, size = {512, 512},
}
