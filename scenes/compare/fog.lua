-- Issue 17's comparison: a ball lens above a box of fog (volume caustics).
-- --set technique=plain|beams: only beams show a volume caustic; the other
-- caustics techniques light surfaces, not the medium (the point of this
-- scene). plain is the fog's own single scattering (volume_light) without it.
local c = require "caustica"
local technique = c.param("technique", "beams")
local scene = c.scene { camera = c.camera { eye = {-3, 0.5, 0}, target = {0, 0.5, 0}, fov = 30 }, background = {0, 0, 0} }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene.medium = c.medium { sigma_s = {0.5, 0.4, 0.3}, sigma_a = {0.1, 0.2, 0.3}, box = {{-1, 0, -1}, {1, 1, 1}} }
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4, segments = 128 }, position = {0, 1.6, 0},
                     material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
if technique == "beams" then
  g:add("caustics", c.pass.beam_caustics { light = sun })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance" })
  g:add("fog", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth", add = "caustics.inscatter" })
else
  assert(technique == "plain", "technique: plain or beams expected, got " .. tostring(technique))
  g:add("shade", c.pass.shade { shadow = "shadow.depth" })
  g:add("fog", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth" })
end
g:output("fog.color")
return { scene = scene, graph = g, size = {256, 256},
         -- bench --sweep technique=all / choose: each technique at its defaults and these settings
         techniques = {
           metric = "caustic", -- the volume caustic (the reference's caustic part includes it)
           { "plain", sweep = { ["fog.steps"] = {16, 64} } },
           { "beams", points = { { ["caustics.refine"] = 0 }, { ["caustics.refine"] = 2 },
                                 { ["caustics.grid"] = 32, ["caustics.refine"] = 2 }, { ["fog.steps"] = 16 } } },
         } }
