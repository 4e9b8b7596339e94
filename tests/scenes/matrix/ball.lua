-- Optics matrix: a ball lens in the sun (issue 27). A glass ball of radius
-- 0.5 and IOR `ior` (no absorption), the sun straight above it, the floor
-- `floor` radii below its centre (1.25: before the paraxial focus n R /
-- (2 (n - 1)) = 1.5 radii at n = 1.5; 1.5: at it; 2.5: beyond). An
-- orthographic camera between the ball and the floor looks straight down
-- at the floor's square [-0.55, 0.55]^2; the output is the caustics pass's
-- irradiance there.
-- --set technique=NAME, ior=, floor=, fresnel=true|false, segments=, scale= (the
-- whole case: radius, floor, camera and its near plane)
local c = require "caustica"
local caustics_pass = require "caustics_pass"
local S = c.param("scale", 1) -- the whole case scaled (the irradiance is not)
local R = 0.5 * S
local floor_y = -c.param("floor", 1.5) * R
local scene = c.scene {
  camera = c.camera { eye = {0, floor_y + 0.5 * (-R - floor_y), 0}, target = {0, floor_y, 0}, up = {0, 0, -1},
                      near = c.param("near", 0.01) * S, ortho = { width = 2.2 * R } },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 * S }, position = {0, floor_y, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = R, segments = c.param("segments", 128) },
                     material = c.material.glass { ior = c.param("ior", 1.5), fresnel = c.param("fresnel", false),
                                                   absorption = {0, 0, 0} } })
local g = c.graph()
g:add("caustics", caustics_pass(c.param("technique", "photon_caustics"), sun))
g:output("caustics.irradiance")
return { scene = scene, graph = g, size = {c.param("size", 128), c.param("size", 128)} }
