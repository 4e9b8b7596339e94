-- A glass ball's caustic under a pane (issue 50): a sun straight above, an
-- orange pane of thin-walled glass (c.material.glass { thin = true }) above
-- a glass ball over a floor. The light reaching the ball has crossed the
-- pane: its caustic is (1 - F) x tint of the bare ball's, in the reference
-- (its photons cross panes) and on the GPU, where photon_caustics reads the
-- sun's shadow map and its pane filter. --set pane=false: no pane;
-- shadow=false: photon_caustics without the shadow map (the pane unseen);
-- technique=layered_caustics, beam_caustics or illumination_textures: that
-- caustics pass instead;
-- technique=caustic_volumes: a rippled pool in place of the ball, its
-- caustics by caustic volumes, the surface by water_surface.
-- below=true: the pane between the ball and the floor instead (0.2 above
-- the floor), where no caustics pass dims the caustic by it (each says so;
-- the reference's photons cross it).
local c = require "caustica"
local scene = c.scene {
  camera = c.camera { eye = {0, 2.6, 2.2}, target = {0, 0, 0}, fov = 40 },
  background = {0.3, 0.3, 0.32},
  ambient = {0.05, 0.05, 0.05},
}
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1.5, 1.5, 1.5} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.7, 0.7, 0.7} } })
local technique = c.param("technique", "photon_caustics")
local water
if technique == "caustic_volumes" then
  water = scene:add(c.water { size = {1.4, 1.4}, resolution = 64, depth = 0.5, position = {0, 0.5, 0} })
  water:drop(0.1, -0.05, 0.3, 0.03)
  water:step(0.4)
else
  scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3, segments = 96 }, position = {0, 0.75, 0},
                       material = c.material.glass { ior = 1.5 } })
end
if c.param("pane", true) then
  scene:add(c.object { mesh = c.mesh.plane { size = 1.0 }, position = {0, c.param("below", false) and 0.2 or 1.6, 0},
                       material = c.material.glass { thin = true, ior = 1.5, tint = {1, 0.6, 0.2} } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
local shadow = c.param("shadow", true) and "shadow.depth" or nil
if water then
  g:add("photons", c.pass.caustic_volumes { light = sun, water = water, shadow = shadow })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance", specular = false })
  g:add("glass", c.pass.water_surface { water = water, color = "shade.color", depth = "shade.depth",
                                        position = "shade.position" })
else
  g:add("photons", c.pass[technique] { light = sun, shadow = shadow })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
end
g:output("glass.color")
return { scene = scene, graph = g, size = {128, 128} }
