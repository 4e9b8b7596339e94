-- Hu & Qin Fig. 26: a glass ring that both reflects and refracts the light
-- of a spot lamp: refractive and reflective caustics on the floor (two
-- photon passes, one per path, added by shade).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 1.6, 2.2}, target = {0, 0.2, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.035},
}
local lamp = scene:add(c.light.spot { position = {1.2, 2.2, 0.6}, direction = {-1.2, -2.2, -0.6}, angle = 30,
                                      intensity = {16, 15, 14} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.75, 0.75} } })
scene:add(c.object { mesh = c.mesh.torus { radius = 0.4, tube = 0.08, segments = 96, sides = 32 }, position = {0, 0.25, 0},
                     rotation = c.quat.axis_angle({1, 0, 0}, 0.5), material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("refracted", c.pass.photon_caustics { light = lamp, buffer = 512, texture = 512, mode = "refract" })
g:add("reflected", c.pass.photon_caustics { light = lamp, buffer = 512, texture = 512, mode = "reflect" })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = {"refracted.irradiance", "reflected.irradiance"} })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
