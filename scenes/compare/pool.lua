-- Issue 17's comparison: a pool under a moving light (water caustics).
-- --set technique=plain|volumes|photons|beams: Sandberg & Falemo's caustic
-- volumes, Hu & Qin's photons through the one-interface water, Liktor &
-- Dachsbacher's beams through it, or none; the surface is refraction-mapped
-- (water_surface) in every case.
local c = require "caustica"
local pool = require "caustica.pool"
local technique = c.param("technique", "volumes")
local scene = c.scene {
  camera = c.camera { eye = {0, 2.3, 2.0}, target = {0, -0.45, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.05, 0.06},
}
local sun = scene:add(c.light.directional { direction = {0.4, -1, 0.2}, intensity = {2.2, 2.1, 1.9} })
local water, volumes_graph = pool.build(scene, { grid = 64, depth = 0.6, light = sun })
local drops = pool.drops(water, 2)
local g = volumes_graph
if technique ~= "volumes" then
  local passes = {
    photons = function() return c.pass.photon_caustics { light = sun } end,
    beams = function() return c.pass.beam_caustics { light = sun } end,
  }
  g = c.graph()
  g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
  if technique ~= "plain" then
    assert(passes[technique], "technique: plain, volumes, photons or beams expected, got " .. tostring(technique))
    g:add("caustics", passes[technique]())
  end
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = technique ~= "plain" and "caustics.irradiance" or nil,
                                specular = false })
  g:add("surface", c.pass.water_surface { water = water, color = "shade.color", depth = "shade.depth",
                                          position = "shade.position" })
  g:output("surface.color")
end
return {
  scene = scene, graph = g,
  update = function(t, dt)
    local e, a = math.rad(60), 0.3 * t
    sun.direction = { math.cos(e) * math.cos(a), -math.sin(e), math.cos(e) * math.sin(a) }
    drops(t, dt)
  end,
  frames = 150, fps = 30, size = {256, 256},
  -- bench --sweep technique=all / choose: each technique at its defaults and these settings
  techniques = {
    metric = "caustic",
    { "plain" },
    { "volumes", sweep = { ["cv.resolution"] = {32, 128, 256} } },
    { "photons", points = { { ["caustics.buffer"] = 128, ["caustics.texture"] = 128 },
                            { ["caustics.buffer"] = 512, ["caustics.texture"] = 512 },
                            { ["caustics.accumulate"] = 16 } } },
    { "beams", points = { { ["caustics.refine"] = 0 }, { ["caustics.refine"] = 2 } } },
  },
}
