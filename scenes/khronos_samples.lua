-- The Khronos glTF samples of transmissive materials, as their authors
-- frame them, face-on: --set sample=transmission (TransmissionTest: a grid
-- of spheres, 14 materials: clear, rough, masked and metallic rows under
-- emissive labels), sample=roughness (TransmissionRoughnessTest: tiles at
-- IOR 1.0 to 2.42 by roughness) or sample=attenuation (AttenuationTest:
-- KHR_materials_volume's blue glass, one shade per column). Each file's
-- materials are per primitive; `caustica info` lists what each is drawn as
-- and what of it is ignored.
local c = require "caustica"

local samples = {
  transmission = { file = c.asset "khronos/TransmissionTest/TransmissionTest.glb",
                   eye = {-0.07, 0.12, 2.6}, target = {-0.07, 0.1, 0}, fov = 30 },
  roughness = { file = c.asset "khronos/TransmissionRoughnessTest/TransmissionRoughnessTest.glb",
                eye = {0, 0, 2.6}, target = {0, 0, 0}, fov = 40 },
  attenuation = { file = c.asset "khronos/AttenuationTest/AttenuationTest.glb",
                  eye = {0, 0, 26}, target = {0, 0, 0}, fov = 40 },
}
local name = c.param("sample", "transmission")
local sample = samples[name]
if not sample then
  error("--set sample=" .. tostring(name) .. ": expected transmission, roughness or attenuation", 0)
end

local scene = c.scene {
  camera = c.camera { eye = sample.eye, target = sample.target, fov = sample.fov },
  background = {0.3, 0.3, 0.32},
  ambient = {0.25, 0.25, 0.25},
}
local sun = scene:add(c.light.directional { direction = {-0.25, -0.5, -1}, intensity = {2.2, 2.2, 2.1} })
local model = scene:add(c.object { mesh = c.mesh.load(sample.file) })
-- --set one_material=true: every part in the first one's material, what a
-- loader that keeps one material per mesh showed (the tests' contrast)
if c.param("one_material", false) then model.material = model.materials[1] end

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("photons", c.pass.photon_caustics { light = sun, shadow = "shadow.depth" }) -- (its pane filter: thin glass between the sun and the glass)
local refraction = c.param("refraction", true)
-- with refraction after it, shade leaves glass and mirrors to it (their
-- alphaMode holes show what lies behind them, not shade's drawing of them)
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance", specular = not refraction })
if refraction then
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
  g:output("glass.color")
else
  -- --set refraction=false: shade's one interface alone, the glass absorbing
  -- over KHR_materials_volume's thicknessFactor (what a pass that cannot
  -- trace the thickness stands in for it with)
  g:output("shade.color")
end

return { scene = scene, graph = g, size = {256, 256}, model = model }
