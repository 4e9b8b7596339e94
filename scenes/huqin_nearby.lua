-- Hu & Qin Fig. 18: a refractor of IOR 1.0 in front of nearby objects
-- should not distort them; through uncorrected impostor rectangles it does,
-- the iterative correction (Fig. 16) removes most of it.
-- --set correction=0|3, ior=, hide=true
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.45, 2.4}, target = {0, 0.35, 0}, fov = 40 },
                        environment = c.cubemap(c.asset "env/room"), ambient = {0.05, 0.05, 0.05} }
local convex = c.param("convex", false)   -- convex objects lit from the camera's side: no shadows to disagree on
if convex then
  scene:add(c.light.directional { direction = {0.8, -0.2, -0.55}, intensity = {2.5, 2.4, 2.2} })
  scene:add(c.object { mesh = c.mesh.box { size = {0.5, 0.5, 0.5} }, position = {0.1, 0.3, -0.7},
                       rotation = c.quat.axis_angle({0, 1, 0}, 0.6), material = c.material.diffuse { color = {0.8, 0.75, 0.6} } })
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.25, segments = 48 }, position = {-0.45, 0.45, -1.0},
                       material = c.material.diffuse { color = {0.7, 0.3, 0.2} } })
else
  scene:add(c.light.directional { direction = {-0.3, -1, -0.6}, intensity = {2.5, 2.4, 2.2} })
  local bunny = c.mesh.load(c.asset "bunny_15k.glb")
  scene:add(c.object { mesh = bunny, position = {0.05, -bunny.bounds[1][2], -0.7},
                       material = c.material.diffuse { color = {0.8, 0.75, 0.6} } })
  local teapot = c.mesh.load(c.asset "teapot.glb")
  scene:add(c.object { mesh = teapot, position = {-0.55, -0.7 * teapot.bounds[1][2], -0.9}, scale = {0.7, 0.7, 0.7},
                       material = c.material.diffuse { color = {0.7, 0.3, 0.2} } })
end
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3, segments = 64 }, position = {0, 0.4, 0.3},
                                  material = c.material.glass { ior = c.param("ior", 1.0) } })
ball.visible = not c.param("hide", false)
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth", correction = c.param("correction", 3),
                                   impostor = c.param("impostor", 512), method = c.param("method", "huqin"),
                                   -- the paper's impostors (Fig. 18); "scene" is the pass's default
                                   lookup = c.param("lookup", "impostors") })
g:output("glass.color")
return { scene = scene, graph = g, size = {256, 256} }
