-- Loads the mesh named by --set path=... (relative to this folder): used by
-- the error-path tests for broken glTF files.
local c = require "caustica"
local path = c.param("path", "scenes/assets/teapot.glb")
local scene = c.scene { camera = c.camera { eye = {0, 0.5, 2}, target = {0, 0, 0} } }
scene:add(c.light.directional { direction = {-0.3, -1, -0.2}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.load(path) })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {64, 64} }
