-- Chaudhari 2008, Fig. 4.1: the dragon refracted through its front and back
-- interfaces only (--set method=huqin: Hu & Qin's two-sided refraction, or
-- method=wyman) against through every interface (layered_refraction, the
-- default), IOR 1.25, in an environment. --set model=800k for the full
-- dragon (the test-sized 40K one is the default).
local c = require "caustica"
local method = c.param("method", "layered")
local scene = c.scene {
  camera = c.camera { eye = {0.1, 0.25, 1.6}, target = {0, 0.02, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
}
local mesh = c.mesh.load(c.param("model", "40k") == "800k" and(c.asset "dragon_800k.glb") or(c.asset "dragon_40k.glb"))
scene:add(c.object { mesh = mesh, material = c.material.glass { ior = c.param("ior", 1.25) },
                     rotation = c.quat.axis_angle({0, 1, 0}, 0.5) })
local g = c.graph()
if method == "layered" then
  g:add("shade", c.pass.shade { specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = c.param("layers", 16),
                                             voxels = c.param("voxels", 256), search = c.param("search", 5) })
else
  g:add("shade", c.pass.shade {})
  g:add("glass", c.pass.refraction { method = method, color = "shade.color" })
end
g:output("glass.color")
return { scene = scene, graph = g, size = {512, 512} }
