-- glTF's alphaMode on a mirror and on solid glass (issue 50): a ball of
-- radius 0.5 before a checkered wall over a floor, a sun from the upper
-- right, drawn by `refraction`. Its material is one of
-- tests/data/cut_specular.gltf's (made by make_cut_specular.py), by
-- --set material=N:
--   1 a mirror with holes: alphaMode MASK by a texture of bands, every
--     other one cut out: the wall, and the ball's inner side, seen through
--     them, and a banded shadow;
--   2 a half mirror: alphaMode BLEND at alpha 0.5, over the wall;
--   3 solid glass with holes: MASK by the same bands;
--   4 half glass: BLEND at 0.5.
-- --set whole=true: the same mirror or glass without alpha (the contrast);
-- view=PASS: that view technique instead of refraction; caustics=true: the
-- sun's caustics by photon_caustics (which draws the ball whole, and says so).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0.3, 2.6}, target = {0, 0, 0}, fov = 40 },
  background = {0.35, 0.4, 0.5},
  ambient = {0.15, 0.15, 0.15},
}
local sun = scene:add(c.light.directional { direction = {-0.5, -0.8, -0.4}, intensity = {2, 2, 2} })
local checker = c.texture.checker { size = 8, a = {0.9, 0.85, 0.8}, b = {0.15, 0.2, 0.3} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0.5, -1.2},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = checker } })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.6, 0},
                     material = c.material.diffuse { color = {0.7, 0.7, 0.7} } })
local which = c.param("material", 1)
local ball = c.mesh.sphere { radius = 0.5, segments = 64 }
if c.param("whole", false) then
  ball.materials[1] = which <= 2 and c.material.mirror {} or c.material.glass { ior = 1.5 }
else
  ball.materials[1] = c.mesh.load("../data/cut_specular.gltf").materials[which]
end
scene:add(c.object { mesh = ball, position = {0, -0.05, 0} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
local caustics = c.param("caustics", false)
if caustics then g:add("caustics", c.pass.photon_caustics { light = sun, shadow = "shadow.depth" }) end
-- shade_specular=true: shade draws the ball too, under the view technique,
-- which would fill its holes (graph_lint says so)
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = c.param("shade_specular", false),
                              caustics = caustics and "caustics.irradiance" or nil })
g:add("view", c.pass[c.param("view", "refraction")] { color = "shade.color", depth = "shade.depth" })
g:output("view.color")
return { scene = scene, graph = g, size = {128, 128} }
