-- Optics matrix: an IOR-1.0 glass sphere before a checkered wall and a box
-- on a floor must vanish (issue 27): the image with the sphere equals the
-- image without it. A directional light with no shadow pass lights
-- everything the same with or without the sphere.
-- --set technique=refraction|refraction_impostors|layered_refraction|sliced_refraction,
--       ortho=true|false, sphere=false (the truth), fresnel=true|false, ior=, inside=true (the camera
--       inside the sphere, looking out at the wall)
local c = require "caustica"
local technique = c.param("technique", "refraction")
local inside = c.param("inside", false)
local eye = inside and {0.1, 0.85, 0.75} or {0, 1.2, 4.0}
local target = inside and {0, 0.8, -2} or {0, 0.8, 0}
local scene = c.scene {
  camera = c.param("ortho", false)
    and c.camera { eye = eye, target = target, ortho = { width = inside and 2.0 or 3.2 }, near = c.param("near", 0.1) }
    or c.camera { eye = eye, target = target, fov = inside and 60 or 45, near = c.param("near", 0.1) },
  background = {0.2, 0.3, 0.5},
  ambient = {0.1, 0.1, 0.1},
}
scene:add(c.light.directional { direction = {-0.3, -1, -0.6}, intensity = {2.5, 2.4, 2.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, material = c.material.diffuse { color = {0.7, 0.68, 0.62} } })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, 1.5, -2.0},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = c.texture.checker { size = 12 } } })
scene:add(c.object { mesh = c.mesh.box { size = {0.5, 0.9, 0.5} }, position = {0.4, 0.45, -0.9},
                     material = c.material.diffuse { color = {0.8, 0.3, 0.2} } })
if c.param("sphere", true) then
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.55, segments = 96 }, position = {0, 0.8, 0.6},
                       material = c.material.glass { ior = c.param("ior", 1.0), fresnel = c.param("fresnel", false),
                                                     absorption = {0, 0, 0} } })
end
local g = c.graph()
if technique == "refraction" or technique == "refraction_impostors" then
  g:add("shade", c.pass.shade {})
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth",
                                      lookup = technique == "refraction" and "scene" or "impostors" })
elseif technique == "layered_refraction" then
  g:add("shade", c.pass.shade { specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
else
  g:add("shade", c.pass.shade { specular = false })
  g:add("glass", c.pass.sliced_refraction { color = "shade.color" })
end
g:output("glass.color")
return { scene = scene, graph = g, size = {128, 128} }
