-- The Stanford dragon at 804K triangles (the size of the 871K scan that
-- Chaudhari's thesis deforms), swaying under a GPU deformer evaluated once
-- per frame into the buffers every pass draws from.
local c = require "caustica"

local amplitude = c.param("amplitude", 0.12)
local speed = c.param("speed", 1.5)

local scene = c.scene {
  camera = c.camera { eye = {0.2, 0.9, 1.9}, target = {0, 0.3, 0}, fov = 40 },
  background = {0.02, 0.02, 0.03},
  ambient = {0.03, 0.03, 0.03},
}
local sun = scene:add(c.light.spot { position = {1.2, 2.4, 1.6}, direction = {-1.2, -2.2, -1.6}, angle = 30,
                                     intensity = {14, 13, 12} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse { color = {0.7, 0.7, 0.7} } })
local dragon_mesh = c.mesh.load(c.asset "dragon_800k.glb")
local dragon = scene:add(c.object {
  mesh = dragon_mesh,
  material = c.material.diffuse { color = {0.75, 0.55, 0.3} },
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
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")

return { scene = scene, graph = g, frames = 90, fps = 30, size = {512, 512} }
