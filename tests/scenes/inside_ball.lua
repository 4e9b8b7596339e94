-- The camera inside a glass ball (IOR 1.5) 1.25 above a checkered floor,
-- looking down through it (issue 52): the floor it sees lies in the ball's
-- shadow with the ball's focus in it. The view through the ball comes
-- from `refraction`'s lookups or layered_refraction's; shade draws the
-- glass or not (specular=), so the input shows the floor (with its shadow
-- and caustic) or the glass.
-- --set technique=refraction|layered_refraction, specular=true|false,
--       photons=true|false, outside=true (the camera above the ball), out=
local c = require "caustica"
local R = 0.5
local scene = c.scene {
  camera = c.camera { eye = c.param("outside", false) and {0.05, 0.7, 0.05} or {0.05, 0.1, 0.05},
                      target = {0, -1.25, 0}, up = {0, 0, -1}, fov = 60, near = 0.01 },
  background = {0.2, 0.3, 0.5}, ambient = {0.1, 0.1, 0.1},
}
local sun = scene:add(c.light.directional { direction = {0.2, -1, 0.1}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, -1.25, 0},
                     material = c.material.diffuse { color = c.texture.checker { size = 16 } } })
scene:add(c.object { mesh = c.mesh.sphere { radius = R, segments = 128 },
                     material = c.material.glass { ior = c.param("ior", 1.5), fresnel = false, absorption = {0, 0, 0} } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
local caustics = c.param("photons", true)
if caustics then
  g:add("caustics", c.pass.photon_caustics { light = sun })
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics and "caustics.irradiance" or nil,
                              specular = c.param("specular", true) })
if c.param("technique", "refraction") == "refraction" then
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
else
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
end
g:output(c.param("out", "glass.color"))
return { scene = scene, graph = g, size = {128, 128} }
