-- A glass sphere in the environment for the refraction pass's stability
-- tests: --set ior=, method=, hide=true, view=front|grazing|near, default_depth=true (no depth given)
local c = require "caustica"
local ior = c.param("ior", 1.5)
local method = c.param("method", "huqin")
local view = c.param("view", "front")
local cameras = {
  front = c.camera { eye = {0, 0.2, 2.4}, target = {0, 0, 0}, fov = 40 },
  grazing = c.camera { eye = {0, 0.05, 2.0}, target = {1.0, 0.0, 0.0}, fov = 60 },   -- the sphere at the image's edge
  near = c.camera { eye = {0, 0, 0.62}, target = {0, 0, 0}, fov = 60, near = 0.05 },  -- the sphere touches the near plane
}
local scene = c.scene { camera = cameras[view], environment = c.cubemap "../../scenes/assets/env/room" }
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.6, segments = 64 },
                                  material = c.material.glass { ior = ior, absorption = {0.1, 0.2, 0.3} } })
ball.visible = not c.param("hide", false)
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { method = method, color = "shade.color",
                                    depth = (not c.param("default_depth", false)) and "shade.depth" or nil,
                                    iterations = c.param("iterations", 3) })
g:output("glass.color")
return { scene = scene, graph = g, size = {64, 64} }
