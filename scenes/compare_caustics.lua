-- One scene for every surface-caustics technique: a glass ball over a
-- diffuse floor and a box under a directional light; --set
-- technique=photons (Hu & Qin's photon buffer), illumination (Iwasaki et
-- al.'s illumination textures), layered (Chaudhari's photons through
-- every interface) or plain (no caustics), so that `caustica bench
-- --sweep technique=...` puts them side by side against the reference.
local c = require "caustica"
local technique = c.param("technique", "illumination")
local scene = c.scene {
  camera = c.camera { eye = {0, 1.6, 2.6}, target = {0, -0.2, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.03, 0.03, 0.03},
}
local e = math.rad(c.param("elevation", 70))
local sun = scene:add(c.light.directional { direction = {0.35 * math.cos(e), -math.sin(e), -0.9 * math.cos(e)},
                                            intensity = {2.5, 2.4, 2.2} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.6, 0},
                     material = c.material.diffuse { color = {0.75, 0.75, 0.72} } })
scene:add(c.object { mesh = c.mesh.box { size = {0.4, 0.4, 0.4} }, position = {0.75, -0.4, -0.5},
                     material = c.material.diffuse { color = {0.7, 0.45, 0.3} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.35, segments = 64 }, position = {0, 0.0, 0},
                     material = c.material.glass { ior = c.param("ior", 1.5) } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
local caustics = nil
if technique == "photons" then
  g:add("caustics", c.pass.photon_caustics { light = sun })
  caustics = "caustics.irradiance"
elseif technique == "illumination" then
  g:add("caustics", c.pass.illumination_textures { light = sun, table = c.param("table", 16) })
  caustics = "caustics.irradiance"
elseif technique == "layered" then
  g:add("caustics", c.pass.layered_caustics { light = sun })
  caustics = "caustics.irradiance"
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics, specular = false })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output(c.param("output", "glass.color"))
-- --set moving=true: the light turns slowly, so nothing is reused between frames
local moving = c.param("moving", false)
return { scene = scene, graph = g, size = {256, 256}, frames = 60,
         update = function(t, dt)
           if moving then
             local a = 0.3 * t
             sun.direction = { 0.35 * math.cos(e) * math.cos(a) - 0.9 * math.cos(e) * math.sin(a), -math.sin(e),
                               0.35 * math.cos(e) * math.sin(a) - 0.9 * math.cos(e) * math.cos(a) }
           end
         end }
