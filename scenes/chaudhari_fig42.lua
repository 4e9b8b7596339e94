-- Chaudhari 2008, Fig. 4.2: the Stanford dragon at 804K triangles (the
-- 871K scan's stand-in) as glass, swaying under a GLSL deformer evaluated
-- once per frame, refracted through every interface (layered_refraction)
-- and casting caustics through every interface onto the floor
-- (layered_caustics). No precomputation: every frame voxelizes and peels
-- the deformed mesh again. --set model=40k for the 40K-triangle dragon,
-- --set method=huqin for the two-interface refraction pass instead.
local c = require "caustica"

local amplitude = c.param("amplitude", 0.12)
local speed = c.param("speed", 1.5)
local model = c.param("model", "800k")
local method = c.param("method", "layered")

local scene = c.scene {
  camera = c.camera { eye = {0.2, 0.9, 1.9}, target = {0, 0.3, 0}, fov = 40 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.05, 0.05, 0.05},
}
local sun = scene:add(c.light.spot { position = {1.2, 2.4, 1.6}, direction = {-1.2, -2.2, -1.6}, angle = 30,
                                     intensity = {14, 13, 12} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 },
                     material = c.material.diffuse { color = c.texture.checker { size = 16, a = {0.75, 0.75, 0.72},
                                                                                  b = {0.45, 0.45, 0.5} } } })
local dragon_mesh = c.mesh.load(model == "40k" and(c.asset "dragon_40k.glb") or(c.asset "dragon_800k.glb"))
local dragon = scene:add(c.object {
  mesh = dragon_mesh,
  material = c.material.glass { ior = c.param("ior", 1.25), absorption = {0.4, 0.2, 0.05} },
  position = {0, -dragon_mesh.bounds[1][2], 0},
})
-- A sway that grows with height (the base stays on the floor): a bend about
-- the vertical axis, phase travelling along the body.
dragon.deform = c.deform.glsl(string.format([[
  vec3 deform(vec3 p, float t) {
    float h = clamp(p.y + 0.5, 0.0, 1.0);
    float a = %f * h * h * sin(%f * t + 3.0 * p.x);
    return vec3(p.x + a, p.y, p.z + 0.5 * a);
  }
]], amplitude, speed))

local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 2048 })
if method == "layered" then
  g:add("caustics", c.pass.layered_caustics { light = sun, buffer = 512, layers = 8 })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
  g:add("glass", c.pass.layered_refraction { color = "shade.color", layers = 16 })
else
  g:add("photons", c.pass.photon_caustics { light = sun, buffer = 512, texture = 512 })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
  g:add("glass", c.pass.refraction { color = "shade.color" })
end
g:output(c.param("output", "glass.color"))

return { scene = scene, graph = g, frames = 90, fps = 30, size = {512, 512} }
