-- Iwasaki et al., Fig. 6(c): a glass teapot over the Happy Buddha, casting
-- caustics on it (the transport table of a 4.7K-vertex teapot at 12 x 12
-- directions: about 24 MB, built once).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0.2, 0.9, 2.3}, target = {0, 0.35, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.04},
}
local sun = scene:add(c.light.directional { direction = {-0.2, -1, -0.3}, intensity = {2.4, 2.3, 2.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse { color = {0.6, 0.6, 0.6} } })
local buddha = c.mesh.load(c.asset "buddha_60k.glb")
scene:add(c.object { mesh = buddha, material = c.material.diffuse { color = {0.85, 0.75, 0.55} },
                     position = {0, -1.0 * buddha.bounds[1][2], 0}, scale = {1.0, 1.0, 1.0} })
local teapot = c.mesh.load(c.asset "teapot.glb")
scene:add(c.object { mesh = teapot, material = c.material.glass { ior = 1.5 }, position = {0.05, 1.3, 0.05},
                     scale = {0.5, 0.5, 0.5}, rotation = c.quat.axis_angle({0, 1, 0}, 0.6) })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
g:add("caustics", c.pass.illumination_textures { light = sun, table = 12 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {640, 480} }
