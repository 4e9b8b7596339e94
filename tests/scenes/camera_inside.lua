-- The camera inside a closed opaque box (inside=box) warns; beside an open plane
-- (inside=plane) or with nothing around it (inside=none) it does not (tests/cli/errors_test.sh).
local c = require "caustica"
local inside = c.param("inside", "box")
local scene = c.scene { camera = c.camera { eye = {0, 0, 0.2}, target = {0, 0, -1}, fov = 60 } }
local l = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
if inside == "box" then
  scene:add(c.object { mesh = c.mesh.box { size = {1, 1, 1} }, material = c.material.diffuse {} })
elseif inside == "plane" then
  scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.5, 0}, material = c.material.diffuse {} })
end
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.2 }, position = {0, 0, -3}, material = c.material.diffuse {} })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32} }
