-- A glTF file's own scene (issue 51): its objects where its node tree puts
-- them, seen through its camera number `camera`, under a sun and an
-- ambient sky. --set path=FILE (relative to scenes/assets), camera=N,
-- animation=N (played on the scene clock; 0: all), size=PX; a path from / is
-- taken as it is
local c = require "caustica"
local path = c.param("path", "khronos/Cameras/Cameras.gltf")
local file = c.gltf.load(path:sub(1, 1) == "/" and path or c.asset(path))
local scene = c.scene { ambient = {0.3, 0.3, 0.3}, background = {0, 0, 0} }
for _, o in ipairs(file.objects) do scene:add(o) end
local cam = file.cameras[c.param("camera", 1)] or file.framing_camera()
if cam then scene.camera = cam end
local sun = scene:add(c.light.directional { direction = {-0.3, -1, -0.5}, intensity = {1, 1, 1} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
-- animation = 0: all of the file's animations at once
local which = c.param("animation", 1)
local anims = which == 0 and file.animations or { file.animations[which] }
local anim = anims[1]
for _, a in ipairs(anims) do if a.duration > anim.duration then anim = a end end
return {
  scene = scene, graph = g, size = {c.param("size", 128), c.param("size", 128)},
  frames = anim and math.max(1, math.floor(anim.duration * 24 + 0.5)) or 1, fps = 24,
  update = function(t)
    for _, a in ipairs(anims) do a:apply(t) end
    if cam then scene.camera = cam end
  end,
}
