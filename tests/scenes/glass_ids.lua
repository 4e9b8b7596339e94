-- A glass ball (object 2, radius 0.5 at the origin) before a diffuse wall (object 1, at z = -1) seen
-- from z = 3: the EXR's first surface gives the glass its objectId (2) and the distance of its front
-- (2.5) where the refraction pass draws it, the wall 4 around it, +inf past the wall
-- (tests/cli/exr_test.sh).
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0, 3}, target = {0, 0, 0}, fov = 40 },
                        environment = c.cubemap(c.asset "env/room") }
scene:add(c.light.directional { direction = {0, 0, -1}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 2 }, position = {0, 0, -1},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2) })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5, segments = 64 }, material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
g:add("glass", c.pass.refraction { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {48, 48} }
