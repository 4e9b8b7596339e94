-- A glass of water as one glTF file (scenes/assets/glass_of_water.gltf,
-- written by make_glass_of_water.py): three primitives, three materials:
-- the glass (IOR 1.5), the water in it (IOR 1.33, absorbing a little red)
-- and a paper label with round windows cut out (alphaMode MASK). One
-- c.mesh.load, one object; `caustica info` lists its three materials.
-- A spot light from the upper left throws the glass's caustic onto the
-- table (layered caustics: every interface, as the layered refraction the
-- camera sees through).
local c = require "caustica"

local scene = c.scene {
  camera = c.camera { eye = {0.2, 1.0, 2.1}, target = {0, 0.35, 0}, fov = 35 },
  background = {0.05, 0.05, 0.06},
  ambient = {0.06, 0.06, 0.07},
}
local lamp = scene:add(c.light.spot { position = {-1.2, 2.4, 0.6}, direction = {1.2, -2.4, -0.6}, angle = 22,
                                      softness = 0.3, intensity = {14, 13.5, 12.5} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.75, 0.72, 0.66} } })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 2, -1.2},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = c.texture.checker { size = 8, a = {0.8, 0.8, 0.8},
                                                                                 b = {0.3, 0.35, 0.45} } } })
local glass = scene:add(c.object { mesh = c.mesh.load(c.asset "glass_of_water.gltf"),
                                   rotation = c.quat.axis_angle({0, 1, 0}, c.param("turn", 0.3)) })

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("caustics", c.pass.layered_caustics { light = lamp })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output("glass.color")

return { scene = scene, graph = g, size = {256, 256}, glass = glass }
