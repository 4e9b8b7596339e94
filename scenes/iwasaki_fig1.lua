-- Iwasaki et al., Fig. 1: a glass ball casting caustics and a shadow on a
-- teapot (and the floor), under a directional light; the camera orbits, so
-- the illumination textures are made once and reused every frame (the
-- paper's central claim: caustics independent of the viewpoint). --set
-- moving=light turns the light instead (every frame rebuilds them).
-- 640x480 as the paper. The refracted view is the paper's sliced object
-- images with one slice (sliced_refraction, as Fig. 1); the targets are the
-- teapot and the floor (`targets`; --set targets=teapot for the teapot alone).
local c = require "caustica"
local moving = c.param("moving", "camera")
local scene = c.scene {
  camera = c.camera { eye = {0, 1.1, 2.4}, target = {0, 0.1, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.04},
}
local e0 = math.rad(55)
local sun = scene:add(c.light.directional { direction = {-0.55 * math.cos(e0), -math.sin(e0), -0.75 * math.cos(e0)},
                                            intensity = {2.4, 2.3, 2.1} })
local floor = scene:add(c.object { mesh = c.mesh.plane { size = 6 }, position = {0, -0.35, 0},
                                  material = c.material.diffuse { color = {0.7, 0.7, 0.68} } })
local teapot = c.mesh.load(c.asset "teapot.glb")
local pot = scene:add(c.object { mesh = teapot, material = c.material.diffuse { color = {0.85, 0.8, 0.7} },
                     position = {-0.15, -0.35 - 0.8 * teapot.bounds[1][2], -0.35}, scale = {0.8, 0.8, 0.8} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.22, segments = 48 }, position = {0.3, 0.35, 0.25},
                     material = c.material.glass { ior = c.param("ior", 1.5) } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
local targets = c.param("targets", "all") == "teapot" and { pot } or { pot, floor }
g:add("caustics", c.pass.illumination_textures { light = sun, planes = c.param("planes", 16), targets = targets })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:add("glass", c.pass.sliced_refraction { color = "shade.color", slices = 1 })
g:output(c.param("output", "glass.color"))
return {
  scene = scene, graph = g, frames = 120, fps = 30, size = {640, 480},
  update = function(t, dt)
    if moving == "light" then
      local a = 0.4 * t
      sun.direction = { -0.55 * math.cos(e0) * math.cos(a) + 0.75 * math.cos(e0) * math.sin(a), -math.sin(e0),
                        -0.55 * math.cos(e0) * math.sin(a) - 0.75 * math.cos(e0) * math.cos(a) }
    else
      scene.camera.eye = c.anim.orbit(t, 2.55, 1.1, 0.05)
    end
  end,
}
