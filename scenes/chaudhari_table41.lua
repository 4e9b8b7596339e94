-- Chaudhari 2008, Table 4.1 and Table 4.2's split: one glass model in an
-- environment at the view of highest depth complexity the thesis reports
-- for, refracted through every interface; --set model=bunny15k|bunny69k|
-- armadillo86k|dragon40k|dragon200k|dragon800k, layers=16|32, size. Timed
-- with `caustica render --timings`, whose stages split the pass into the
-- parts that scale with triangles (bounds, voxelize, attributes: one
-- draw each) and those that scale with pixels and depth complexity (peel,
-- ranges, trace): examples/chaudhari_scaling/measure.sh runs them all.
local c = require "caustica"
local files = {
  bunny15k = c.asset "bunny_15k.glb", bunny69k = c.asset "bunny_69k.glb", armadillo86k = c.asset "armadillo_86k.glb",
  dragon40k = c.asset "dragon_40k.glb", dragon200k = c.asset "dragon_200k.glb", dragon800k = c.asset "dragon_800k.glb",
}
local model = c.param("model", "bunny15k")
local file = files[model]
if not file then error("model: one of bunny15k, bunny69k, armadillo86k, dragon40k, dragon200k, dragon800k") end
local scene = c.scene {
  camera = c.camera { eye = {0.0, 0.2, 1.7}, target = {0, 0, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
}
-- seen from the side, where the most surfaces overlap along a view ray
scene:add(c.object { mesh = c.mesh.load(file), material = c.material.glass { ior = 1.25 },
                     rotation = c.quat.axis_angle({0, 1, 0}, c.param("turn", 1.3)) })
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = c.param("layers", 32),
                                           voxels = c.param("voxels", 256) })
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
