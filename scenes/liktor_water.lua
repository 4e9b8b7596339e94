-- Liktor & Dachsbacher 2011, Fig. 1 right and Table 1 "Water": a glass
-- sphere focuses a spot light onto a tank of murky water, whose surface
-- refracts the beams again (the edge rays are traced through the sphere's
-- two interfaces and the water's one: multi-bounce beams, §6). The volume
-- caustics are under water, the surface caustics on the tank's floor; the
-- camera looks through the tank's (invisible) side. 2 refinement and 2 edge
-- steps: the rippled water and the lens's silhouette need them (README).
-- --set grid=, refine=, edges= (silhouette refinement), wave= (the
-- surface's ripple amplitude, 0: flat), technique=beams|plain,
-- smooth=false (one area function per beam), blur= (the surface caustics'
-- filter, pixels).
local c = require "caustica"

local technique = c.param("technique", "beams")
local wave = c.param("wave", 0.02)
local scene = c.scene {
  -- just under the water level, looking down so that no view ray meets the surface from below
  camera = c.camera { eye = {0.2, -0.15, 2.3}, target = {0.2, -0.99, 0}, fov = 40 },
  background = {0, 0, 0},
  ambient = {0.01, 0.012, 0.015},
}
local light = scene:add(c.light.spot { position = {0.15, 3.0, 0.1}, direction = {-0.15, -3.0, -0.1}, angle = 16,
                                       intensity = {10, 10, 10} })
scene:add(c.object { mesh = c.mesh.plane { size = 2 }, position = {0, -1, 0},
                     material = c.material.diffuse { color = {0.8, 0.78, 0.7} } })
scene:add(c.object { mesh = c.mesh.plane { size = 2 }, position = {0, -0.5, -1}, rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     scale = {1, 1, 0.5}, material = c.material.diffuse { color = {0.3, 0.35, 0.45} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3, segments = 96 }, position = {0, 0.6, 0},
                     material = c.material.glass { ior = c.param("ior", 1.35) } })
local water = scene:add(c.water { size = 2, resolution = 65, depth = 1, ior = 1.33, attenuation = {0.05, 0.03, 0.02} })
local function ripple(t)
  water:set_heights(function(x, z)
    return wave * math.sin(2 * math.pi * (x / 0.6 + 0.3 * t)) * math.cos(2 * math.pi * (z / 0.8 - 0.2 * t))
  end)
end
if wave > 0 then ripple(0) end
-- the murky water: a medium box under the surface
scene.medium = c.medium { sigma_s = {0.35, 0.4, 0.45}, sigma_a = {0.03, 0.02, 0.02}, box = {{-1, -1, -1}, {1, 0, 1}} }

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = light, size = 1024 })
if technique == "beams" then
  g:add("beams", c.pass.beam_caustics { light = light, grid = c.param("grid", 16), refine = c.param("refine", 2), edges = c.param("edges", 2),
                                        smooth = c.param("smooth", true), blur = c.param("blur", 1.5) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "beams.irradiance", specular = false })
  g:add("water", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth", add = "beams.inscatter" })
elseif technique == "plain" then
  g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
  g:add("water", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth" })
else
  error("technique: beams or plain expected, got " .. tostring(technique))
end
g:output("water.color")

return {
  scene = scene, graph = g,
  update = function(t) if wave > 0 then ripple(t) end end,
  frames = 60, fps = 30, size = {512, 512},
}
