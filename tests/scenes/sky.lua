-- The procedural sky (scenes/assets/env/sky.hdr, one equirectangular .hdr
-- loaded with c.environment; env= another file) seen by a narrow camera:
-- --set look=sun|ground.
local c = require "caustica"
local look = c.param("look", "sun")
local target = look == "sun" and {0.45, 0.55, -0.70} or {0.3, -1, 0.2}
local scene = c.scene {
  camera = c.camera { eye = {0, 0, 0}, target = target, fov = c.param("fov", 4) },
  environment = c.environment(c.param("env", "../../scenes/assets/env/sky.hdr")),
}
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {16, 16} }
