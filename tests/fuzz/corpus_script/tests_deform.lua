-- A grid bent by a deformer: --set mode=none|wave|glsl|broken.
local c = require "caustica"
local mode = c.param("mode", "wave")
local scene = c.scene { camera = c.camera { eye = {0, 2.2, 2.2}, target = {0, 0, 0}, fov = 45 } }
scene:add(c.light.directional { direction = {-0.4, -1, -0.3}, intensity = {2.5, 2.5, 2.5} })
local sheet = scene:add(c.object { mesh = c.mesh.grid { size = 2, resolution = 64 },
                                   material = c.material.diffuse { color = {0.6, 0.7, 0.8} } })
if mode == "wave" then
  sheet.deform = c.deform.wave { amplitude = 0.15, frequency = 6, speed = 3, direction = {1, 0, 0} }
elseif mode == "glsl" then
  -- the same wave, written as GLSL
  sheet.deform = c.deform.glsl [[
    vec3 deform(vec3 p, float t) {
      return p + vec3(0.0, 0.15 * sin(6.0 * p.x - 3.0 * t), 0.0);
    }
  ]]
elseif mode == "broken" then
  sheet.deform = c.deform.glsl [[
    vec3 deform(vec3 p, float t) {
      return p + undefined_variable;
    }
  ]]
end
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {96, 96}, frames = 30, fps = 30 }
