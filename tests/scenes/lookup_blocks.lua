-- The distance map and the impostors as building blocks (issue 54,
-- tests/cli/lookup_blocks_test.sh). `--set case=`:
--   default    refraction; the graph adds its distance map
--   named      the script's own distance_map in its place
--   impostors  lookup = "impostors": an impostors block, no map
--   imp_named  the script's own impostors in its place
--   two        two refraction passes at one size: one map
--   sizes      the second at another size: two maps
--   beams      beam_caustics too: a map of distances beside refraction's radiance
--   wrong      a map of distances given to refraction
--   photons    photon_caustics and refraction's impostors at one size: one set
--   recursion  refraction with recursion = 1: a set made every frame
--   layered    layered_refraction (nearby); `--set nearby=false`: no set
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
local caustics
if case == "beams" then
  g:add("beams", c.pass.beam_caustics { light = sun })
  caustics = "beams.irradiance"
elseif case == "photons" then
  g:add("photons", c.pass.photon_caustics { light = sun, texture = 256, shadow = "shadow.depth" })
  caustics = "photons.irradiance"
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false, caustics = caustics })
if case == "layered" then
  g:add("glass", c.pass.layered_refraction { color = "shade.color", nearby = c.param("nearby", true) })
  g:output("glass.color")
  return { scene = scene, graph = g, size = {64, 64}, frames = 3 }
end
if case == "named" or case == "wrong" then
  g:add("dm", c.pass.distance_map { shadow = "shadow.depth", content = case == "wrong" and "distances" or nil })
elseif case == "imp_named" then
  g:add("imp", c.pass.impostors { shadow = "shadow.depth" })
end
local impostor_lookup = case == "impostors" or case == "imp_named" or case == "photons"
g:add("glass", c.pass.refraction { color = "shade.color", shadow = "shadow.depth",
                                   lookup = impostor_lookup and "impostors" or nil,
                                   recursion = case == "recursion" and 1 or nil,
                                   distance_map = (case == "named" or case == "wrong") and "dm.map" or nil,
                                   impostors = case == "imp_named" and "imp.set" or nil })
if case == "two" or case == "sizes" then
  -- the same glass drawn again over the first (for the count of maps)
  g:add("again", c.pass.refraction { color = "glass.color", depth = "shade.depth", shadow = "shadow.depth",
                                     impostor = case == "sizes" and 128 or nil })
  g:output("again.color")
else
  g:output("glass.color")
end
return { scene = scene, graph = g, size = {64, 64}, frames = 3 }
