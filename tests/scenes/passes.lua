-- User passes: --set mode=fullscreen|custom|broken_shader|misspelt_uniform|late_input|prune|environment
local c = require "caustica"
local mode = c.param("mode", "fullscreen")
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0.3, 0} },
                        environment = c.cubemap "../../scenes/assets/env/room" }
scene:add(c.light.point { position = {1, 3, 1}, intensity = {6, 6, 6} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, position = {0, 0.4, 0},
                     material = c.material.mirror {} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 } })
local g = c.graph()
if mode == "fullscreen" then
  g:add("shade", c.pass.shade {})
  g:add("invert", c.pass.fullscreen { shader = "invert.frag", inputs = { image = "shade.color" },
                                      uniforms = { gain = 0.5 } })
  g:output("invert.color")
elseif mode == "custom" then
  g:add("fill", c.pass.custom { outputs = { color = "rgba32f" },
    run = function(ctx) ctx:clear("color", {0.25, 0.5, 0.75, 1}) end })
  g:output("fill.color")
elseif mode == "broken_shader" then
  g:add("shade", c.pass.shade {})
  g:add("bad", c.pass.fullscreen { shader = "broken.frag", inputs = { image = "shade.color" } })
  g:output("bad.color")
elseif mode == "misspelt_uniform" then
  -- `gian` for `gain`: invert.frag declares no such uniform
  g:add("shade", c.pass.shade {})
  g:add("invert", c.pass.fullscreen { shader = "invert.frag", inputs = { image = "shade.color" },
                                      uniforms = { gian = 0.5 } })
  g:output("invert.color")
elseif mode == "late_input" then
  g:add("invert", c.pass.fullscreen { shader = "invert.frag", inputs = { image = "shade.color" } })
  g:add("shade", c.pass.shade {})
  g:output("invert.color")
elseif mode == "prune" then
  g:add("unused", c.pass.environment {})
  g:add("shade", c.pass.shade {})
  g:output("shade.color")
elseif mode == "environment" then
  g:add("env", c.pass.environment {})
  g:add("shade", c.pass.shade { background = "env.color" })
  g:output("shade.color")
elseif mode == "env_only" then
  g:add("env", c.pass.environment {})
  g:output("env.color")
end
return { scene = scene, graph = g, size = {64, 64} }
