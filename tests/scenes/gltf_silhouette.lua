-- A glTF file's objects posed by its animation `animation` at `time`
-- seconds, flat white on black through an orthographic camera looking
-- down -z, `width` wide about (cx, cy): the silhouette tests/lua/
-- gltf_scene_test.lua compares with its own skinning of the file.
local c = require "caustica"
local file = c.gltf.load(c.asset(c.param("path", "khronos/RiggedSimple/RiggedSimple.glb")))
local scene = c.scene { ambient = {1, 1, 1}, background = {0, 0, 0} }
for _, o in ipairs(file.objects) do
  o.material = c.material.diffuse { color = {1, 1, 1} }
  scene:add(o)
end
local anim = file.animations[c.param("animation", 1)]
if anim then anim:apply(c.param("time", 0) - anim.start, { loop = false }) end -- time on the file's clock
local cx, cy, w = c.param("cx", 0), c.param("cy", 0), c.param("width", 2)
scene.camera = c.camera { eye = {cx, cy, 1000}, target = {cx, cy, 0}, ortho = { width = w }, near = 1, far = 2000 }
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {c.param("size", 64), c.param("size", 64)} }
