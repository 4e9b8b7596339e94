-- A glass sphere over a floor under a spot light: the caustic it focuses
-- is the test bed for the reference's convergence (README) and for the
-- caustics techniques. --set sky=true: under a procedural sky (one
-- equirectangular .hdr, scenes/assets/env/sky.hdr) instead of the room.
local c = require "caustica"

local ior = c.param("ior", 1.5)
local radius = c.param("radius", 0.35)

local scene = c.scene {
  camera = c.camera { eye = {0, 1.4, 2.4}, target = {0, 0.2, 0}, fov = 40 },
  environment = c.param("sky", false) and c.environment(c.asset "env/sky.hdr") or c.cubemap(c.asset "env/room"),
}
local lamp = scene:add(c.light.spot { position = {0.6, 2.6, 0.4}, direction = {-0.6, -2.6, -0.4}, angle = 25,
                                      softness = 0.3, intensity = {12, 11.6, 10.8} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.8, 0.8, 0.78} } })
scene:add(c.object { mesh = c.mesh.sphere { radius = radius, segments = 128 }, position = {0, radius + 0.15, 0},
                     material = c.material.glass { ior = ior } })

local techniques = c.param("techniques", true)   -- false: plain shading only
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
if techniques then
  g:add("photons", c.pass.photon_caustics { light = lamp, buffer = c.param("buffer", 256), k = c.param("k", 0) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth", iterations = c.param("iterations", 3) })
  g:output("glass.color")
else
  g:add("shade", c.pass.shade { shadow = "shadow.depth" })
  g:output("shade.color")
end

return { scene = scene, graph = g, size = {256, 256} }
