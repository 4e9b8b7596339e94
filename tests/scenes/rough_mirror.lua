-- Rough mirrors (GGX roughness on a mirror, as glTF's smooth metals): three
-- mirror strips on the ground, roughness 0, r and 2r (--set roughness=r,
-- default 0.15), reflecting an emissive checkered wall behind them. No
-- light: the wall's own radiance is all there is, so no caustic stands
-- between refraction's blur of the reflection (a cone lookup) and the
-- reference's sampled microfacets (rough_glass.lua's counterpart).
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.7, 2.4}, target = {0, 0.25, -0.6}, fov = 40 },
                        background = {0.2, 0.2, 0.2}, ambient = {0, 0, 0} }
local checker = c.texture.checker { size = 12, a = {0.9, 0.9, 0.9}, b = {0.1, 0.1, 0.1} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 1.5, -1.2},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = {0, 0, 0}, emission = checker } })
local r = c.param("roughness", 0.15)
for i, x in ipairs { -0.7, 0, 0.7 } do
  scene:add(c.object { mesh = c.mesh.plane { size = {0.6, 2} }, position = {x, 0, 0},
                       material = c.material.mirror { roughness = (i - 1) * r, color = {0.95, 0.9, 0.8} } })
end
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("mirrors", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("mirrors.color")
return { scene = scene, graph = g, size = {192, 128} }
