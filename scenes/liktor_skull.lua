-- Liktor & Dachsbacher 2011, Fig. 1 left and Table 1 "Skull": a glass skull
-- over a floor in fog, lit by a spot light from above. Its light is
-- refracted through both sides of the glass (beam_caustics traces each
-- edge ray through every interface) into volume caustics in the fog and
-- surface caustics on the floor; volume_light adds the fog's single
-- scattering of the direct light, shadowed (Fig. 8). --set grid=, refine=,
-- volumes=tight|prism, technique=beams|plain, fog= (sigma_s), turn= (the
-- skull's turn per second).
-- edges= (silhouette refinement), smooth=false (one area function per
-- beam), blur= (the surface caustics' filter, pixels).
local c = require "caustica"

local technique = c.param("technique", "beams")
local fog = c.param("fog", 0.25)
local scene = c.scene {
  camera = c.camera { eye = {2.3, 1.1, 2.4}, target = {0, 0.75, 0}, fov = 42 },
  background = {0, 0, 0},
  ambient = {0.01, 0.01, 0.012},
}
local light = scene:add(c.light.spot { position = {0.25, 3.2, 0.2}, direction = {-0.25, -3.2, -0.2}, angle = 22,
                                       intensity = {14, 13.5, 12.5} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse { color = {0.75, 0.72, 0.68} } })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, 1.5, -1.6}, rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = {0.35, 0.4, 0.5} } })
local skull = scene:add(c.object { mesh = c.mesh.load(c.asset "skull.glb"), position = {0, 1.45, 0}, scale = {0.9, 0.9, 0.9},
                                   material = c.material.glass { ior = 1.5 } })
scene.medium = c.medium { sigma_s = {fog, fog, fog}, sigma_a = {0.02, 0.02, 0.02}, box = {{-2, 0, -1.6}, {2, 2.6, 2}} }

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = light, size = 1024 })
if technique == "beams" then
  g:add("beams", c.pass.beam_caustics { light = light, grid = c.param("grid", 16), refine = c.param("refine", 1), edges = c.param("edges", 0),
                                        smooth = c.param("smooth", true), blur = c.param("blur", 1.5),
                                        volumes = c.param("volumes", "tight") })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "beams.irradiance", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  g:add("fog", c.pass.volume_light { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth",
                                     add = "beams.inscatter" })
elseif technique == "plain" then
  g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  g:add("fog", c.pass.volume_light { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth" })
else
  error("technique: beams or plain expected, got " .. tostring(technique))
end
g:output("fog.color")

local turn = c.param("turn", 0.4)
return {
  scene = scene, graph = g,
  update = function(t) skull.rotation = c.quat.axis_angle({0, 1, 0}, turn * t) end,
  frames = 60, fps = 30, size = {512, 512},
}
