-- Hu & Qin Fig. 10 and 11: a refractive sphere in an environment map, IOR
-- 0.8 (Fig. 10: n_t < n_i) or 1.75 (Fig. 11), by Hu & Qin's method or
-- Wyman's (the baseline): --set ior=1.75 --set method=wyman
local c = require "caustica"
local ior = c.param("ior", 1.75)
local method = c.param("method", "huqin")
local iterations = c.param("iterations", 3)

local scene = c.scene {
  camera = c.camera { eye = {0, 0.4, 2.6}, target = {0, 0, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
}
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.7, segments = 96 }, material = c.material.glass { ior = ior, fresnel = c.param("fresnel", true) } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { method = method, color = "shade.color", depth = "shade.depth", iterations = iterations,
                                   internal = c.param("internal", 4) })
g:output("glass.color")
return { scene = scene, graph = g, size = {256, 256} }
