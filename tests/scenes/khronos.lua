-- Khronos glTF samples of materials as their READMEs show them (issue 50),
-- for both renderers: --set sample=NAME, one of the names below. Each is
-- framed by its bounds (centred, scaled to a radius of 1) from the side its
-- README's screenshot shows, under a sun from the upper left behind the
-- camera and an ambient sky; a sun's shadow map, `shade`, `glossy_reflection`
-- (--set glossy=false: without it) and `refraction` where the sample has
-- glass or mirrors. The assets are copies in
-- scenes/assets/khronos (see its README for their licences).
local c = require "caustica"
local samples = {
  texture_transform = { file = "TextureTransformTest/TextureTransformTest.gltf" },
  texture_settings = { file = "TextureSettingsTest/TextureSettingsTest.glb" },
  normal_tangent = { file = "NormalTangentTest/NormalTangentTest.glb" },
  normal_tangent_mirror = { file = "NormalTangentMirrorTest/NormalTangentMirrorTest.glb" },
  damaged_helmet = { file = "DamagedHelmet/DamagedHelmet.glb" },
  candle_holder = { file = "GlassHurricaneCandleHolder/GlassHurricaneCandleHolder.glb", eye = {0, 0.35, 1} },
  vase = { file = "GlassVaseFlowers/GlassVaseFlowers.glb", eye = {0, 0.3, 1} },
  specular = { file = "SpecularTest/SpecularTest.glb" },
  alpha_blend = { file = "AlphaBlendModeTest/AlphaBlendModeTest.glb", eye = {0, 0.25, 1} },
  clearcoat = { file = "ClearCoatTest/ClearCoatTest.glb", scale = 1.1, target = {0.3, 0.02, 0} },
  toy_car = { file = "ToyCar/ToyCar.gltf", eye = {0.6, 0.45, 1}, scale = 2.4, target = {0, 0.62, 0} },
}
local name = c.param("sample", "texture_transform")
local sample = samples[name]
if not sample then
  local names = {}
  for k in pairs(samples) do names[#names + 1] = k end
  table.sort(names)
  error("--set sample=" .. tostring(name) .. ": expected one of " .. table.concat(names, ", "), 0)
end
local mesh = c.mesh.load(c.asset("khronos/" .. sample.file))
local lo, hi = mesh.bounds[1], mesh.bounds[2]
local radius = 0
for i = 1, 3 do radius = math.max(radius, (hi[i] - lo[i]) / 2) end
local s = (sample.scale or 1) / radius
local eye = sample.eye or {0, 0, 1}
local d = 3.2 / math.sqrt(eye[1] ^ 2 + eye[2] ^ 2 + eye[3] ^ 2)
local scene = c.scene {
  camera = c.camera { eye = {eye[1] * d, eye[2] * d, eye[3] * d}, target = sample.target or {0, 0, 0}, fov = 40,
                      near = 0.05, far = 20 },
  background = {0.3, 0.3, 0.32},
  ambient = {0.25, 0.25, 0.25},
}
local sun = scene:add(c.light.directional { direction = {0.35, -0.5, -1}, intensity = {2.2, 2.2, 2.1} })
local model = scene:add(c.object { mesh = mesh, scale = {s, s, s},
                                   position = {-(lo[1] + hi[1]) / 2 * s, -(lo[2] + hi[2]) / 2 * s,
                                               -(lo[3] + hi[3]) / 2 * s} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
local color = "shade.color"
if c.param("glossy", true) then
  g:add("glossy", c.pass.glossy_reflection { color = "shade.color" })
  color = "glossy.color"
end
g:add("glass", c.pass.refraction { color = color, depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {c.param("size", 192), c.param("size", 192)}, model = model }
