-- A sphere above a floor under one light of the kind named by --set kind=.
local c = require "caustica"
local kind = c.param("kind", "point")
local intensity = c.param("intensity", 6.0)
local scene = c.scene {
  camera = c.camera { eye = {0, 3, 3}, target = {0, 0, 0}, fov = 50 },
  background = {0, 0, 0},
}
local light
if kind == "point" then
  light = c.light.point { position = {0, 2.5, 0}, intensity = {intensity, intensity, intensity} }
elseif kind == "directional" then
  light = c.light.directional { direction = {0, -1, 0}, intensity = {intensity / 3, intensity / 3, intensity / 3} }
elseif kind == "spot" then
  light = c.light.spot { position = {0, 2.5, 0}, direction = {0, -1, 0}, angle = 40, softness = 0.2,
                         intensity = {intensity, intensity, intensity} }
elseif kind == "linear" then
  light = c.light.linear { start = {-0.5, 2.5, 0}, ["end"] = {0.5, 2.5, 0}, samples = 8,
                           intensity = {intensity, intensity, intensity} }
else
  error("unknown light kind '" .. kind .. "'")
end
scene:add(light)
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse { color = {0.8, 0.8, 0.8} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5, segments = 48 }, position = {0, 1.0, 0},
                     material = c.material.diffuse { color = {0.7, 0.3, 0.3} } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = light, size = 512 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
return { scene = scene, graph = g, size = {96, 96} }
