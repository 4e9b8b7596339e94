-- shaders/common/fresnel.glsl tabulated by a fullscreen pass
-- (tests/scenes/fresnel_grid.frag): 64 cosines by 8 IOR ratios.
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0, 1}, target = {0, 0, 0} } }
local g = c.graph()
g:add("table", c.pass.fullscreen { shader = "fresnel_grid.frag" })
g:output("table.color")
return { scene = scene, graph = g, size = {64, 8} }
