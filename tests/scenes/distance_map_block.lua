-- The distance map as a building block (issue 54, tests/cli/distance_map_test.sh):
-- `--set case=` default (the graph adds it), named (the script's own), impostors
-- (a lookup that reads none), two (two readers, one map), sizes (two sizes, two
-- maps), beams (radiance for refraction, distances for beam_caustics), wrong (a
-- map of distances given to refraction).
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1.2, 2.4}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0.3, -1, -0.2}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0},
                     material = c.material.diffuse { color = {0.8, 0.7, 0.5} } })
scene:add(c.object { mesh = c.mesh.box { size = {0.4, 0.6, 0.4} }, position = {-0.7, -0.2, -0.6},
                     material = c.material.diffuse { color = {0.2, 0.4, 0.8} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35 }, position = {0.1, -0.1, 0},
                     material = c.material.glass { ior = 1.5 } })
local case = c.param("case", "default")
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
if case == "beams" then
  g:add("beams", c.pass.beam_caustics { light = sun })
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false,
                              caustics = case == "beams" and "beams.irradiance" or nil })
if case == "named" or case == "wrong" then
  g:add("dm", c.pass.distance_map { shadow = "shadow.depth", content = case == "wrong" and "distances" or nil })
end
g:add("glass", c.pass.refraction { color = "shade.color", shadow = "shadow.depth",
                                   lookup = case == "impostors" and "impostors" or nil,
                                   distance_map = (case == "named" or case == "wrong") and "dm.map" or nil })
if case == "two" or case == "sizes" then
  -- a second view of the same glass over the first (a mirror-like double exposure, for the count)
  g:add("again", c.pass.refraction { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth",
                                     impostor = case == "sizes" and 128 or nil })
  g:output("again.color")
else
  g:output("glass.color")
end
return { scene = scene, graph = g, size = {64, 64}, frames = 3 }
