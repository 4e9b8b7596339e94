-- Hu & Qin Fig. 29: a fully dynamic scene, no preprocessing: a glass
-- dinosaur morphing (into a blob, the morph target we have) while it
-- refracts a Buddha behind it and casts caustics.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 1.2, 2.4}, target = {0, 0.4, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.035},
}
local lamp = scene:add(c.light.point { position = {0.8, 2.4, 1.2}, intensity = {8, 7.7, 7.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
local buddha = c.mesh.load(c.asset "buddha_60k.glb")
scene:add(c.object { mesh = buddha, position = {0, -0.9 * buddha.bounds[1][2], -0.9}, scale = {0.9, 0.9, 0.9},
                     material = c.material.diffuse { color = {0.85, 0.7, 0.4} } })
local dino_mesh = c.mesh.load(c.asset "dinosaur_morph.glb")
local dino = scene:add(c.object { mesh = dino_mesh, position = {0, -1.4 * dino_mesh.bounds[1][2], 0.1},
                                  scale = {1.4, 1.4, 1.4}, rotation = c.quat.axis_angle({0, 1, 0}, -0.5),
                                  material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("photons", c.pass.photon_caustics { light = lamp, buffer = 256, texture = 512 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return {
  scene = scene, graph = g,
  update = function(t, dt) dino.morph_weights = { c.anim.pingpong(t, 4) } end,
  frames = 120, fps = 30, size = {512, 512},
}
