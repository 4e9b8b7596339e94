-- A box of fog under a directional light, seen from the side. --set
-- density=homogeneous|linear, g=, thickness= (scales the coefficients;
-- 0: a medium that does nothing), ball=true (a glass ball above the fog
-- focusing a volume caustic into it), ior=, hide=true, ball_y=, stretch=
-- (the ball long along z: a line focus), inside=true (the camera in the fog
-- under the ball, looking up the beams), ortho=true (an orthographic camera
-- 2.4 wide: the image's sum is the power scattered towards it),
-- technique=plain|beams|photons (the GPU graph: plain shading, beam_caustics
-- and volume_light, or photon_caustics and volume_light), grid=, refine=, volumes=tight|prism, max_focus=,
-- reflection=, output=color|inscatter|irradiance.
local c = require "caustica"
local mode = c.param("density", "homogeneous")
local g = c.param("g", 0.0)
local ball = c.param("ball", false)
local ior = c.param("ior", 1.5)
local size = c.param("size", 33)

local scene = c.scene {
  -- looking along +x through the fog box [-1,1] x [0,1] x [-1,1] at height 0.5
  camera = c.param("inside", false) and c.camera { eye = {0.02, 0.3, 0.01}, target = {0, 1.6, 0}, up = {1, 0, 0}, fov = 60 }
           or c.param("ortho", false) and c.camera { eye = {-3, 0.5, 0}, target = {0, 0.5, 0}, ortho = { width = 2.4 } }
           or c.camera { eye = {-3, 0.5, 0}, target = {0, 0.5, 0}, fov = 30 },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
local density = 1.0
if mode == "linear" then
  density = function(x, y, z) return 0.5 + 1.5 * y end   -- trilinear grids hold a linear function exactly
end
local k = c.param("thickness", 1.0) -- scales both coefficients (0: a medium that does nothing)
scene.medium = c.medium { sigma_s = {0.5 * k, 0.4 * k, 0.3 * k}, sigma_a = {0.1 * k, 0.2 * k, 0.3 * k}, g = g, density = density,
                          resolution = {4, 9, 4}, box = {{-1, 0, -1}, {1, 1, 1}} }
if ball then
  local stretch = c.param("stretch", 1.0) -- > 1: an ellipsoid long along z, focusing to a line
  local sphere = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4, segments = 128 }, position = {0, c.param("ball_y", 1.6), 0},
                                      scale = {1, 1, stretch}, material = c.material.glass { ior = ior } })
  sphere.visible = not c.param("hide", false)
end
local technique = c.param("technique", "plain")
local gr = c.graph()
if technique == "beams" then
  local light = sun
  gr:add("shadow", c.pass.shadow_map { light = light, size = 512 })
  gr:add("beams", c.pass.beam_caustics { light = light, grid = c.param("grid", 16), refine = c.param("refine", 1), edges = c.param("edges", 0),
                                         volumes = c.param("volumes", "tight"), max_focus = c.param("max_focus", 1000), reflection = c.param("reflection", true) })
  gr:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "beams.irradiance" })
  gr:add("fog", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth", add = "beams.inscatter" })
  local out = c.param("output", "color")
  gr:output(out == "color" and "fog.color" or "beams." .. out)
elseif technique == "photons" then
  -- caustics on surfaces only: the fog's shaft under the ball is drawn by
  -- no pass, and the graph says so (issue 52)
  gr:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
  gr:add("photons", c.pass.photon_caustics { light = sun })
  gr:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
  gr:add("fog", c.pass.volume_light { color = "shade.color", shadow = "shadow.depth" })
  gr:output("fog.color")
elseif technique == "plain" then
  gr:add("shade", c.pass.shade {})
  gr:output("shade.color")
else
  error("technique: plain, beams or photons expected, got " .. tostring(technique))
end
return { scene = scene, graph = gr, size = {size, size} }
