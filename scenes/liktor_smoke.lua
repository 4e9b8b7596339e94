-- Liktor & Dachsbacher 2011, Table 1 "Smoke": volume caustics in an
-- inhomogeneous medium. A glass sphere focuses a spot light into a plume
-- of smoke given by a density function (sampled on a grid); beam_caustics
-- marches the density along each view ray's interval in a beam (4 samples)
-- and volume_light along each pixel's ray. --set grid=, refine=,
-- technique=beams|plain, density= (the plume's peak density).
-- edges= (silhouette refinement), smooth=false (one area function per
-- beam), blur= (the surface caustics' filter, pixels).
local c = require "caustica"

local technique = c.param("technique", "beams")
local peak = c.param("density", 2.0)
local scene = c.scene {
  camera = c.camera { eye = {0, 0.9, 3.4}, target = {0, 0.8, 0}, fov = 40 },
  background = {0, 0, 0},
}
local light = scene:add(c.light.spot { position = {0.1, 3.4, 0.1}, direction = {-0.1, -3.4, -0.1}, angle = 15,
                                       intensity = {12, 11.5, 11} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.6, 0.6, 0.6} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3, segments = 96 }, position = {0, 1.9, 0},
                     material = c.material.glass { ior = 1.5 } })
-- a plume: puffs rising and widening, with a little swirl
local puffs = {}
for i = 0, 7 do
  local y = 0.1 + 0.2 * i
  puffs[#puffs + 1] = { x = 0.15 * math.sin(1.7 * i), y = y, z = 0.12 * math.cos(2.3 * i), r = 0.18 + 0.06 * i }
end
local function density(x, y, z)
  local d = 0
  for _, p in ipairs(puffs) do
    local dx, dy, dz = x - p.x, y - p.y, z - p.z
    d = d + math.exp(-(dx * dx + dy * dy + dz * dz) / (p.r * p.r))
  end
  return peak * math.min(d, 1.5) / 1.5
end
scene.medium = c.medium { sigma_s = {0.8, 0.8, 0.8}, sigma_a = {0.05, 0.05, 0.05}, density = density,
                          resolution = {24, 24, 24}, box = {{-1, 0, -1}, {1, 1.7, 1}} }

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = light, size = 1024 })
if technique == "beams" then
  g:add("beams", c.pass.beam_caustics { light = light, grid = c.param("grid", 16), refine = c.param("refine", 1), edges = c.param("edges", 0),
                                        smooth = c.param("smooth", true), blur = c.param("blur", 1.5) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "beams.irradiance", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  g:add("smoke", c.pass.volume_light { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth",
                                       add = "beams.inscatter" })
elseif technique == "plain" then
  g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  g:add("smoke", c.pass.volume_light { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth" })
else
  error("technique: beams or plain expected, got " .. tostring(technique))
end
g:output("smoke.color")
return { scene = scene, graph = g, frames = 1, size = {512, 512} }
