-- Hu & Qin Fig. 1a: a glass dinosaur refracting a Buddha behind it and
-- reflecting a bunny beside it, with refractive caustics, no preprocessing.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0.3, 1.1, 2.5}, target = {0, 0.4, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.035},
}
local lamp = scene:add(c.light.point { position = {0.5, 2.5, 1.4}, intensity = {8, 7.8, 7.4} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
local buddha = c.mesh.load(c.asset "buddha_60k.glb")
scene:add(c.object { mesh = buddha, position = {-0.15, -0.9 * buddha.bounds[1][2], -0.9}, scale = {0.9, 0.9, 0.9},
                     material = c.material.diffuse { color = {0.85, 0.7, 0.4} } })
local bunny = c.mesh.load(c.asset "bunny_15k.glb")
scene:add(c.object { mesh = bunny, position = {0.75, -0.5 * bunny.bounds[1][2], 0.1}, scale = {0.5, 0.5, 0.5},
                     rotation = c.quat.axis_angle({0, 1, 0}, -1.2), material = c.material.diffuse { color = {0.8, 0.8, 0.78} } })
local dino = c.mesh.load(c.asset "dinosaur_morph.glb")
scene:add(c.object { mesh = dino, position = {-0.1, -1.3 * dino.bounds[1][2], 0.1}, scale = {1.3, 1.3, 1.3},
                     rotation = c.quat.axis_angle({0, 1, 0}, 0.4), material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("photons", c.pass.photon_caustics { light = lamp, buffer = 512, texture = 512, k = 3 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
