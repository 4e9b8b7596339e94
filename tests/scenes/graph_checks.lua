-- Graphs the graph check must refuse or reshape (issue 54), on a glass
-- ball over a floor in the sun. --set case=shadow|refraction|volume_light:
-- that pass reads `second` (default "shadow.depth"; "first.color", a colour
-- image, it must refuse) as a shadow map (tests/cli/typed_inputs_test.sh);
-- case=twice: the script's
-- depth_layers for the sun at `buffer` beside a layered_caustics that names
-- none (tests/cli/blocks_test.sh).
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 2, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0.3, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0}, material = c.material.diffuse {} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass {} })
local g = c.graph()
local case = c.param("case", "shadow")
if case == "twice" then
  g:add("mylayers", c.pass.depth_layers { light = sun, buffer = c.param("buffer", 256) })
  g:add("beams", c.pass.beam_caustics { light = sun, light_layers = "mylayers.layers" })
  g:add("caustics", c.pass.layered_caustics { light = sun })
  g:add("out", c.pass.shade { caustics = { "caustics.irradiance", "beams.irradiance" } })
else
  g:add("shadow", c.pass.shadow_map { light = sun })
  g:add("first", c.pass.shade {})
  local second = c.param("second", "shadow.depth")
  if case == "shadow" then
    g:add("out", c.pass.shade { shadow = { "shadow.depth", second } })
  elseif case == "refraction" then
    g:add("out", c.pass.refraction { color = "first.color", shadow = second })
  else
    g:add("out", c.pass.volume_light { color = "first.color", shadow = second })
  end
end
g:output("out.color")
return { scene = scene, graph = g, size = {32, 32} }
