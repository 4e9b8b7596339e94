-- Issue 8's cube over a floor: a glass cube of IOR 0.8 (light totally
-- reflected off the outside at incidences past 53 degrees) or 2.42 (total
-- internal reflection inside) tilted under a directional light, seen from
-- above. --set ior=, caustics=true|false (photon_caustics or none),
-- mask=true (the cube in white on black, to leave it out of comparisons),
-- view=top (an orthographic camera 5 wide straight down at the floor, the
-- output photon_caustics' irradiance: the floor's caustic light, the cube
-- not drawn), buffer=
local c = require "caustica"
local mask = c.param("mask", false)
local scene = c.scene {
  camera = c.param("view", "") == "top"
           and c.camera { eye = {0, 3, 0}, target = {0, 0, 0}, up = {0, 0, -1}, ortho = { width = 5 } }
           or c.camera { eye = {0.0, 3.0, 1.6}, target = {0, 0, -0.2}, fov = 50 },
  background = {0, 0, 0},
  ambient = {0, 0, 0},
}
local e = math.rad(c.param("elevation", 65))
local sun = scene:add(c.light.directional { direction = {0.3 * math.cos(e), -math.sin(e), -0.95 * math.cos(e)},
                                            intensity = mask and {0, 0, 0} or {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 5 }, material = c.material.diffuse { color = mask and {0, 0, 0} or {0.8, 0.8, 0.8} } })
scene:add(c.object { mesh = c.mesh.box { size = {0.7, 0.7, 0.7} }, position = {0, 0.9, 0},
                     rotation = c.quat.mul(c.quat.axis_angle({0, 1, 0}, math.rad(30)), c.quat.axis_angle({1, 0, 0}, math.rad(35))),
                     material = mask and c.material.diffuse { color = {0, 0, 0}, emission = {1, 1, 1} }
                                     or c.material.glass { ior = c.param("ior", 0.8) } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
local caustics = c.param("caustics", true) and not mask
if caustics then
  g:add("photons", c.pass.photon_caustics { light = sun, buffer = c.param("buffer", 256) })
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics and "photons.irradiance" or nil, specular = false })
g:output(caustics and c.param("view", "") == "top" and "photons.irradiance" or "shade.color")
return { scene = scene, graph = g, size = {128, 128} }
