-- The morphing dinosaur (dinosaur_morph.glb: a T-Rex whose morph target is
-- a blob of the same volume) as glass, refracted through all its
-- interfaces while it morphs, casting caustics from a point light circling
-- it: the layers are taken again every frame from the morphed mesh.
local c = require "caustica"
local morph_period = c.param("morph_period", 4.0)
local scene = c.scene {
  camera = c.camera { eye = {0, 1.2, 2.6}, target = {0, 0.35, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.045},
}
local lamp = scene:add(c.light.point { position = {1.5, 2.5, 1.0}, intensity = {7, 6.6, 6} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 },
                     material = c.material.diffuse { color = c.texture.checker { size = 12, a = {0.78, 0.78, 0.74},
                                                                                  b = {0.5, 0.5, 0.55} } } })
local dino_mesh = c.mesh.load(c.asset "dinosaur_morph.glb")
local dino = scene:add(c.object {
  mesh = dino_mesh,
  material = c.material.glass { ior = c.param("ior", 1.4), absorption = {0.3, 0.1, 0.2} },
  position = {0, -1.4 * dino_mesh.bounds[1][2], 0}, scale = {1.4, 1.4, 1.4},
  rotation = c.quat.axis_angle({0, 1, 0}, -0.6),
})
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("caustics", c.pass.layered_caustics { light = lamp, buffer = 512, layers = 8 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = 16 })
g:output("glass.color")
return {
  scene = scene, graph = g,
  update = function(t, dt)
    lamp.position = c.anim.orbit(t, 1.8, 2.5, 0.125)
    dino.morph_weights = { c.anim.pingpong(t, morph_period) }
  end,
  frames = 120, fps = 30, size = {512, 512},
}
