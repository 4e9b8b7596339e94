-- Issue 17's comparison: a glass ball over a floor (surface caustics).
-- --set technique=plain|photons|illumination|layered|beams: every
-- technique that applies, each at its defaults (sweep its own parameters
-- as caustics.<param>, e.g. --sweep caustics.buffer=128,256,512). The
-- light turns slowly, so nothing is reused between frames; --set turn=R
-- turns it R radians a second instead of 0.3 (0: a still light, 3: a fast
-- one; issue 32's flicker and accumulation are measured on all three).
local c = require "caustica"
local technique = c.param("technique", "layered")
local turn = tonumber(c.param("turn", "0.3"))
local scene = c.scene {
  camera = c.camera { eye = {0, 1.6, 2.6}, target = {0, -0.2, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.03},
}
local e = math.rad(70)
local sun = scene:add(c.light.directional { direction = {0.35 * math.cos(e), -math.sin(e), -0.9 * math.cos(e)},
                                            intensity = {2.5, 2.4, 2.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.6, 0},
                     material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, material = c.material.glass { ior = 1.5 } })
local passes = {
  photons = function() return c.pass.photon_caustics { light = sun } end,
  illumination = function() return c.pass.illumination_textures { light = sun } end,
  layered = function() return c.pass.layered_caustics { light = sun } end,
  beams = function() return c.pass.beam_caustics { light = sun } end,
}
-- A caustics technique registered since (issue 54) joins at its defaults,
-- under its own name: --set technique=NAME, and bench --sweep technique=all.
local newer = c.techniques("caustics", { "photon_caustics", "illumination_textures", "layered_caustics", "beam_caustics" })
for _, name in ipairs(newer) do
  passes[name] = function() return c.pass[name] { light = sun } end
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
if technique ~= "plain" then
  local names = { "plain", "photons", "illumination", "layered", "beams" }
  for _, name in ipairs(newer) do names[#names + 1] = name end
  assert(passes[technique], "technique: " .. table.concat(names, ", ") .. " expected, got " .. tostring(technique))
  g:add("caustics", passes[technique]())
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = technique ~= "plain" and "caustics.irradiance" or nil,
                              specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output("glass.color")
-- bench --sweep technique=all / choose: each technique at its defaults and these settings
local techniques = {
  metric = "caustic",
  { "plain" },
  { "photons", points = { { ["caustics.buffer"] = 128, ["caustics.texture"] = 128 },
                          { ["caustics.buffer"] = 512, ["caustics.texture"] = 512 },
                          { ["caustics.buffer"] = 1024, ["caustics.texture"] = 1024, ["caustics.k"] = 1 },
                          { ["caustics.accumulate"] = 16 },
                          -- issue 32: the cheapest grid, a point per photon, with and without accumulation
                          { ["caustics.buffer"] = 32, ["caustics.footprint"] = 0 },
                          { ["caustics.buffer"] = 32, ["caustics.footprint"] = 0, ["caustics.accumulate"] = 16 } } },
  { "illumination", points = { { ["caustics.planes"] = 8 }, { ["caustics.size"] = 512 },
                               { ["caustics.table"] = 8 } } },
  { "layered", sweep = { ["caustics.buffer"] = {128, 512} } },
  { "beams", points = { { ["caustics.refine"] = 0 }, { ["caustics.refine"] = 2 },
                        { ["caustics.grid"] = 32, ["caustics.refine"] = 2 } } },
}
for _, name in ipairs(newer) do techniques[#techniques + 1] = { name } end -- (at their defaults)
return { scene = scene, graph = g, size = {256, 256}, frames = 60, techniques = techniques,
         update = function(t)
           local a = turn * t
           sun.direction = { 0.35 * math.cos(e) * math.cos(a) - 0.9 * math.cos(e) * math.sin(a), -math.sin(e),
                             0.35 * math.cos(e) * math.sin(a) - 0.9 * math.cos(e) * math.cos(a) }
         end }
