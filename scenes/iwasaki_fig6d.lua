-- Iwasaki et al., Fig. 6(d): glass dolphins under a linear light
-- approximated by 8 point lights, one set of illumination textures each,
-- accumulated (the frame's light list holds the samples).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 1.3, 2.2}, target = {0, 0.1, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.04},
}
local tube = scene:add(c.light.linear { start = {-0.8, 2.0, 0.3}, ["end"] = {0.8, 2.0, 0.3}, samples = 8,
                                        intensity = {10, 9.5, 9} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse { color = {0.65, 0.68, 0.72} } })
local dolphins = c.mesh.load(c.asset "dolphins.glb")
scene:add(c.object { mesh = dolphins, material = c.material.glass { ior = 1.5 }, position = {0, 0.55, 0},
                     scale = {1.2, 1.2, 1.2} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = tube, size = 1024 })
g:add("caustics", c.pass.illumination_textures { light = tube })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {640, 480} }
