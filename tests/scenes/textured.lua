-- Textures on diffuse surfaces (c.texture, c.texture.checker, glTF
-- baseColorTexture / normalTexture / KHR_texture_transform), on the GPU and
-- in the reference alike. A checkered back wall, a glTF box with its PNG
-- texture (Khronos BoxTextured), the KHR_texture_transform quad, a panel
-- with a normal map of ridges (--set normal_map=false: without;
-- flat_normal_map=true: a flat one, tests/data/normal_flat.png; --set
-- emissive=true: glowing with the quadrants image instead), a point light
-- with a shadow map; --set ball=true puts a glass
-- ball in front of the wall (refraction with impostors: the checker seen
-- through it).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 0.3, 4}, target = {0, 0, 0}, fov = 45 },
  background = {0.05, 0.05, 0.05},
  ambient = {0.1, 0.1, 0.1},
}
local checker = c.texture.checker { size = 8, a = {0.9, 0.85, 0.8}, b = {0.15, 0.2, 0.3} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, 0, -1.5},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = checker } })
scene:add(c.object { mesh = c.mesh.load "../../scenes/assets/khronos/BoxTextured/BoxTextured.glb",
                     position = {-1.1, -0.5, 0}, scale = {0.8, 0.8, 0.8},
                     rotation = c.quat.axis_angle({0, 1, 0}, 0.5) })
scene:add(c.object { mesh = c.mesh.load "../data/transform_quad.gltf", position = {0.6, -1.2, -0.5},
                     scale = {0.6, 0.6, 0.6} })
local ridges = c.texture { file = "../data/normal_ridges.png", filter = "linear" }
local flat = c.param("flat_normal_map", false) and c.texture { file = "../data/normal_flat.png", filter = "linear" }
local panel = c.material.diffuse { color = {0.8, 0.8, 0.8},
                                   normal = flat or (c.param("normal_map", true) and ridges or nil) }
if c.param("emissive", false) then
  -- the panel glows with the quadrants image instead (emission x texture)
  panel = c.material.diffuse { color = {0, 0, 0},
                               emission = c.texture { file = "../data/quadrants.png", filter = "nearest" } }
end
scene:add(c.object { mesh = c.mesh.plane { size = 1 }, position = {0.9, 0.5, -0.5},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2), material = panel })
local lamp = c.light.point { position = {0.5, 1.5, 2.5}, intensity = {6, 6, 6} }
scene:add(lamp)
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
if c.param("ball", false) then
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.45, segments = 96 }, position = {-0.2, 0.45, 0.5},
                       material = c.material.glass { ior = 1.5 } })
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
  g:output("glass.color")
else
  g:output("shade.color")
end
return { scene = scene, graph = g, size = {128, 128} }
