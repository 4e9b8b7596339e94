-- Hu & Qin Fig. 28: caustics under a rippling water surface, seen from
-- under water: one interface (the light refracts into the water and stays
-- there), caustics on the floor, a wall and the dolphins. The photon pass
-- at its own defaults (since issue 8; the paper's k = 3 filter at 192^2
-- over the whole receiver, --set k=3 --set texture=192 --set fit=false,
-- blurs the floor's caustic lines into blotches). --set technique=volumes: Sandberg & Falemo's caustic volumes
-- on the same water; --set view=floor: straight down at a patch of the
-- floor from under water (the caustic lines without the surface or the
-- dolphins in front; tests/lua/photon_test.lua).
local c = require "caustica"
local technique = c.param("technique", "photons")
local floor_view = c.param("view", "figure") == "floor"
local scene = c.scene {
  camera = floor_view and c.camera { eye = {0.8, -0.3, 0.7}, target = {0.8, -1, 0.7}, up = {0, 0, -1}, ortho = { width = 0.8 } }
           or c.camera { eye = {0.2, -0.35, 1.3}, target = {-0.1, -0.7, -0.2}, fov = 55 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.02, 0.04, 0.05},
}
local sun = scene:add(c.light.directional { direction = {0.3, -1, -0.2}, intensity = {2.4, 2.3, 2.1} })
local sand = c.material.diffuse { color = {0.75, 0.7, 0.55} }
scene:add(c.object { mesh = c.mesh.plane { size = 3 }, position = {0, -1, 0}, material = sand })
scene:add(c.object { mesh = c.mesh.box { size = {3, 1.1, 0.1} }, position = {0, -0.45, -1.0}, material = sand })
local dolphins = c.mesh.load(c.asset "dolphins.glb")
scene:add(c.object { mesh = dolphins, position = {0, -0.6, -0.2}, scale = {0.7, 0.7, 0.7},
                     material = c.material.diffuse { color = {0.55, 0.6, 0.68} } })
local water = scene:add(c.water { size = 3, resolution = 96, depth = 1.0, attenuation = {0.3, 0.1, 0.06},
                                  damping = 0.2, wave_speed = 0.5 })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
if technique == "volumes" then
  g:add("caustics", c.pass.caustic_volumes { light = sun, water = water })
elseif technique == "photons" then
  g:add("caustics", c.pass.photon_caustics { light = sun, buffer = 512, texture = c.param("texture", 512), k = c.param("k", 0),
                                             fit = c.param("fit", true), bias = 0.08 })
else
  error("technique: photons or volumes expected, got " .. tostring(technique))
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("surface", c.pass.water_surface { water = water, color = "shade.color", depth = "shade.depth",
                                        position = "shade.position" })
g:output("surface.color")
local drop_at = 0
return {
  scene = scene, graph = g,
  update = function(t, dt)
    if t >= drop_at then
      water:drop(0.9 * math.sin(3.1 * t), 0.9 * math.cos(1.7 * t), 0.2, 0.02)
      drop_at = drop_at + 0.25
    end
    water:step(dt)
  end,
  frames = 120, fps = 30, size = {512, 512},
  techniques = {
    metric = "caustic",
    { "photons", points = { { ["caustics.k"] = 3, ["caustics.texture"] = 192 } } },
    { "volumes" },
  },
}
