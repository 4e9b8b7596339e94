-- Partial transmission (glTF's transmissionFactor, c.material.glass {
-- transmission }): three balls of IOR 1.5 before an emissive checkered
-- wall under a sun from the upper left front, transmission 1, t and t/2
-- (--set transmission=t, default 0.6), the rest of each surface diffuse
-- orange. No shadow falls on what is seen (the wall glows and reflects
-- nothing), so the refraction pass's unshadowed diffuse share and the
-- reference's agree but for the light the balls focus onto their own
-- inside, which only the reference has.
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.45, 3}, target = {0, 0.45, 0}, fov = 35 },
                        background = {0.2, 0.2, 0.2}, ambient = {0.05, 0.05, 0.05} }
local sun = scene:add(c.light.directional { direction = {0.4, -0.6, -0.7}, intensity = {1.5, 1.5, 1.5} })
local checker = c.texture.checker { size = 12, a = {0.9, 0.9, 0.9}, b = {0.1, 0.1, 0.1} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.45, -1.5},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2), cast_shadows = false,
                     material = c.material.diffuse { color = {0, 0, 0}, emission = checker } })
local t = c.param("transmission", 0.6)
for i, x in ipairs { -0.8, 0, 0.8 } do
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, position = {x, 0.45, 0},
                       material = c.material.glass { ior = 1.5, transmission = ({1, t, t / 2})[i],
                                                     color = {0.9, 0.45, 0.1} } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth", shadow = "shadow.depth" })
g:output("glass.color")
return { scene = scene, graph = g, size = {192, 128} }
