-- Optics matrix: the floor under a ball lens lit as a user lights it
-- (issue 52): a shadow map, the caustics pass and shade adding both. At
-- IOR 1.0 the ball bends nothing and the floor must read as without it:
-- the shadow's border and the caustic's must meet. The sun `tilt` degrees
-- off the zenith, the floor `floor` radii below the ball's centre, an
-- orthographic camera straight down over 1.6 x 1.6 around the shadow.
-- --set technique=NAME, ior=, floor=, tilt=, ball=false (the truth)
local c = require "caustica"
local caustics_pass = require "caustics_pass"
local R = 0.5
local floor_y = -c.param("floor", 2.5) * R
local tilt = math.rad(c.param("tilt", 0))
local shift = math.tan(tilt) * (-floor_y) -- where the shadow's centre falls
local scene = c.scene {
  camera = c.camera { eye = {shift, floor_y + 0.2, 0}, target = {shift, floor_y, 0}, up = {0, 0, -1}, near = 0.01,
                      ortho = { width = 3.2 * R } },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = {math.sin(tilt), -math.cos(tilt), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, floor_y, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
if c.param("ball", true) then
  scene:add(c.object { mesh = c.mesh.sphere { radius = R, segments = c.param("segments", 128) },
                       material = c.material.glass { ior = c.param("ior", 1.0), fresnel = false,
                                                     absorption = {0, 0, 0} } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("caustics", caustics_pass(c.param("technique", "photon_caustics"), sun))
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:output("shade.color")
return { scene = scene, graph = g, size = {c.param("size", 128), c.param("size", 128)} }
