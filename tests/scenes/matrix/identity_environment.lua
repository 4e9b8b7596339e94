-- Optics matrix: an IOR-1.0 glass cube (or sphere) with nothing but the
-- environment behind it must vanish (issue 52): the image with it equals
-- the image without it. A cube's corners graze the view and its faces
-- send light out of the back and the sides.
-- --set technique=refraction|refraction_impostors|layered_refraction|sliced_refraction,
--       glass=false (the truth), shape=cube|sphere, ior=, ortho=true|false
local c = require "caustica"
local technique = c.param("technique", "sliced_refraction")
local eye, target = {0.4, 0.5, 2.5}, {0, 0, 0}
local scene = c.scene {
  camera = c.param("ortho", false) and c.camera { eye = eye, target = target, ortho = { width = 1.6 } }
           or c.camera { eye = eye, target = target, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
}
if c.param("glass", true) then
  local cube = c.param("shape", "cube") == "cube"
  scene:add(c.object { mesh = cube and c.mesh.box { size = {0.8, 0.8, 0.8} } or c.mesh.sphere { radius = 0.5, segments = 64 },
                       rotation = c.quat.axis_angle({0, 1, 0}, 0.5),
                       material = c.material.glass { ior = c.param("ior", 1.0), fresnel = false, absorption = {0, 0, 0} } })
end
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
if technique == "refraction" or technique == "refraction_impostors" then
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth",
                                      lookup = technique == "refraction" and "scene" or "impostors" })
else
  g:add("glass", c.pass[technique] { color = "shade.color" })
end
g:output("glass.color")
return { scene = scene, graph = g, size = {128, 128} }
