-- Rough glass (GGX roughness, as glTF's rough transmission): three balls of
-- IOR 1.5 before an emissive checkered wall, roughness 0, r and 2r
-- (--set roughness=r, default 0.3); --set tint=true tints them orange
-- (glTF's transmission tint, once per way through). No light: the wall's own radiance is
-- all there is, so no caustic stands between the refraction pass's blur
-- (a cone lookup) and the reference's sampled microfacets.
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.45, 3}, target = {0, 0.45, 0}, fov = 35 },
                        background = {0.2, 0.2, 0.2}, ambient = {0, 0, 0} }
local checker = c.texture.checker { size = 12, a = {0.9, 0.9, 0.9}, b = {0.1, 0.1, 0.1} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.45, -1.5},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = {0, 0, 0}, emission = checker } })
local r = c.param("roughness", 0.3)
local tint = c.param("tint", false) and {1.0, 0.55, 0.2} or {1, 1, 1}
for i, x in ipairs { -0.8, 0, 0.8 } do
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, position = {x, 0.45, 0},
                       material = c.material.glass { ior = 1.5, roughness = (i - 1) * r, tint = tint } })
end
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {192, 128} }
