-- Optics matrix: a glass cube tilted in the sun, its caustic on the floor
-- (issue 27). A cube of side 1 and IOR `ior` (2.42: total internal
-- reflection inside; 0.8: at the way in), an ideal interface (no Fresnel
-- reflection) and no absorption, its centre 1.2 above the floor, turned 35
-- degrees about {1, 0.5, 0.3}, in a sun along {0.3, -1, 0.2}. An
-- orthographic camera looks straight down at the 2.4-wide square of floor
-- under the cube along the light; the output is the caustics pass's
-- irradiance there. tests/lua/closed_forms.lua traces the same cube.
-- --set technique=NAME, ior=, tilt= (the sun that many degrees off the zenith, from the same side)
local c = require "caustica"
local caustics_pass = require "caustics_pass"
local cube = require "cube_geometry"
if c.param("tilt", 0) ~= 0 then cube = cube.tilted(c.param("tilt", 0)) end
local scene = c.scene {
  camera = c.camera { eye = {cube.view_centre[1], 3, cube.view_centre[3]}, target = cube.view_centre, up = {0, 0, -1},
                      ortho = { width = cube.view_width } },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = cube.light, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 12 }, material = c.material.diffuse { color = {1, 1, 1} } })
scene:add(c.object { mesh = c.mesh.box { size = {cube.side, cube.side, cube.side} }, position = cube.centre,
                     rotation = c.quat.axis_angle(cube.axis, math.rad(cube.angle)),
                     material = c.material.glass { ior = c.param("ior", 2.42), fresnel = false, absorption = {0, 0, 0} } })
local g = c.graph()
g:add("caustics", caustics_pass(c.param("technique", "photon_caustics"), sun))
g:output("caustics.irradiance")
return { scene = scene, graph = g, size = {64, 64} }
