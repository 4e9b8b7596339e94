-- A glass ball lens (R = 0.4, n = 1.5) above a box of fog [-1,1] x [0,1] x
-- [-1,1] (sigma_s 0.5, sigma_a 0.1, isotropic), under a vertical sun: the
-- ball focuses a bright cone into the fog (focus 0.6 below its centre, at
-- y = 0.85), inside the dark column of its shadow. Seen from the side,
-- below the ball. Twin of fog_lens.pov.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0.5, 3}, target = {0, 0.5, 0}, fov = 20 },
  background = {0, 0, 0},
}
scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene.medium = c.medium { sigma_s = {0.5, 0.5, 0.5}, sigma_a = {0.1, 0.1, 0.1}, g = 0, density = 1.0,
                          box = {{-1, 0, -1}, {1, 1, 1}} }
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4, segments = 512 }, position = {0, 1.45, 0},
                     material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {128, 128} }
