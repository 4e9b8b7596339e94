-- The demo: a teapot and a glass dinosaur that morphs into a blob and back,
-- on a floor, lit by a point light circling them. The dinosaur refracts the
-- room (Hu & Qin §2.1) and focuses the light into caustics on the floor
-- (Hu & Qin §3); shadows from a cube shadow map.
local c = require "caustica"

local morph_period = c.param("morph_period", 4.0)   -- seconds from dinosaur to blob and back

local scene = c.scene {
  camera = c.camera { eye = {0, 1.6, 3.2}, target = {0, 0.35, 0}, fov = 45 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.035},
}

local lamp = scene:add(c.light.point { position = {1.5, 2.5, 1.0}, intensity = {6, 5.6, 5.0} })

scene:add(c.object {
  mesh = c.mesh.plane { size = 6 },
  material = c.material.diffuse { color = {0.75, 0.75, 0.72} },
})
-- Models are normalised to a unit box centred at the origin: lift each by
-- the bottom of its bounds so it stands on the floor.
local teapot_mesh = c.mesh.load(c.asset "teapot.glb")
scene:add(c.object {
  mesh = teapot_mesh,
  material = c.material.diffuse { color = {0.8, 0.45, 0.25} },
  position = {-0.55, -0.8 * teapot_mesh.bounds[1][2], 0}, scale = {0.8, 0.8, 0.8},
})
local dino_mesh = c.mesh.load(c.asset "dinosaur_morph.glb")
local dino = scene:add(c.object {
  mesh = dino_mesh,
  material = c.material.glass { ior = c.param("ior", 1.5), absorption = {0.3, 0.1, 0.2} },
  position = {0.55, -1.4 * dino_mesh.bounds[1][2], 0}, scale = {1.4, 1.4, 1.4},
  rotation = c.quat.axis_angle({0, 1, 0}, -0.6),
})

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("photons", c.pass.photon_caustics { light = lamp, buffer = 512, texture = 512, k = 3 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")

return {
  scene = scene, graph = g,
  update = function(t, dt)
    lamp.position = c.anim.orbit(t, 1.8, 2.5, 0.125)
    dino.morph_weights = { c.anim.pingpong(t, morph_period) }
  end,
  frames = 120, fps = 30, size = {512, 512},
}
