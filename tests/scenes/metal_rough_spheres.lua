-- The Khronos sample MetalRoughSpheresNoTextures (glTF's metallic-roughness
-- BRDF on spheres of metallic 0..1 by roughness 0..1, issue 50) under a sun
-- and an ambient sky, both renderers. The file is 7 mm across (its node
-- transforms applied): scaled by 1000. Its smooth metals (metallic >= 0.5, roughness <= 0.3, no texture)
-- are mirrors, drawn by `refraction`; the rest by the BRDF in `shade`, the
-- spheres they reflect put in their glossy lobes by `glossy_reflection`.
-- --set graph=shade: shade alone (the mirrors show the background);
-- env=room: the room cube map as the environment (which the mirrors and
-- the BRDF's glossy lobes reflect) instead of a grey background.
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {2.78, 2.74, 14}, target = {2.78, 2.74, 0}, fov = 40, near = 1, far = 40 },
  background = {0.3, 0.3, 0.32},
  environment = c.param("env", "none") == "room" and c.cubemap(c.asset "env/room") or nil,
  ambient = {0.25, 0.25, 0.25},
}
scene:add(c.light.directional { direction = {-0.25, -0.5, -1}, intensity = {2.2, 2.2, 2.1} })
local model = scene:add(c.object { mesh = c.mesh.load(c.asset "khronos/MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb"),
                                   scale = {1000, 1000, 1000} })
local g = c.graph()
g:add("shade", c.pass.shade {})
if c.param("graph", "full") == "shade" then
  g:output("shade.color")
else
  g:add("glossy", c.pass.glossy_reflection { color = "shade.color" })
  g:add("mirrors", c.pass.refraction { color = "glossy.color", depth = "shade.depth" })
  g:output("mirrors.color")
end
return { scene = scene, graph = g, size = {128, 128}, model = model }
