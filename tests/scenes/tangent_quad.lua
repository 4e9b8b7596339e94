-- tests/data/tangent_quad.gltf (make_tangent_quad.py: a quad whose normal
-- map tilts the normal 45 degrees towards the tangent, and whose TANGENT is
-- +z) seen from above under a sun from +z, 27 degrees up; --set
-- tangent=false: tangent_quad_none.gltf, the same without TANGENT (the
-- tangent made from the texture coordinates: +x).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 2, 0.01}, target = {0, 0, 0}, ortho = { width = 1.2 }, near = 0.5, far = 5 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {0, -0.5, -1}, intensity = {2, 2, 2} })
local file = c.param("tangent", true) and "../data/tangent_quad.gltf" or "../data/tangent_quad_none.gltf"
scene:add(c.object { mesh = c.mesh.load(file) })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32} }
