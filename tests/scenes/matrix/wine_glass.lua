-- Optics matrix (issue 52, case 15): a lathed wine glass, its walls `wall`
-- thick (0.012: four surfaces along most of the light through its bowl),
-- standing on a floor under a spot light up and to the left. The camera,
-- orthographic and straight down, sees the floor around the glass, lit by
-- a shadow map, the caustics pass and shade (specular = false: the glass
-- itself is not drawn; the reference draws it, so the matrix compares
-- outside its disc). --set technique=NAME, wall=, glass=false (no glass),
-- solid=true (the bowl filled: two surfaces), buffer= (the pass's photon
-- buffer), cx=, cw= (the view's centre and width), lx= (the light's x).
local c = require "caustica"
local caustics_pass = require "caustics_pass"
local W = c.param("wall", 0.012) -- wall thickness
local outer = { {0, 0}, {0.3, 0}, {0.3, 0.015}, {0.04, 0.03}, {0.03, 0.33}, {0.07, 0.4}, {0.18, 0.47},
                {0.26, 0.57}, {0.3, 0.7}, {0.29, 0.85}, {0.26, 0.95} }
local profile = {}
for _, p in ipairs(outer) do profile[#profile + 1] = p end
if c.param("solid", false) then
  profile[#profile + 1] = {0, 0.95}
else
  -- back down the inside, W in from the outer wall, to the bowl's bottom
  profile[#profile + 1] = {0.26 - W, 0.95}
  for i = #outer - 1, 6, -1 do profile[#profile + 1] = {outer[i][1] - W, outer[i][2] + (i == 6 and W or 0)} end
  profile[#profile + 1] = {0, 0.4 + W}
end
local cx, cw = c.param("cx", 0.4), c.param("cw", 2.0)
local lx = c.param("lx", -0.6)
local scene = c.scene {
  camera = c.camera { eye = {cx, 2.5, 0}, target = {cx, 0, 0}, up = {0, 0, -1}, near = 0.01, ortho = { width = cw } },
  background = {0, 0, 0},
}
local spot = scene:add(c.light.spot { position = {lx, 2.6, 0}, direction = {-lx, 0.7 - 2.6, 0}, angle = 25,
                                      softness = 0, intensity = {4, 4, 4} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, material = c.material.diffuse { color = {1, 1, 1} } })
if c.param("glass", true) then
  scene:add(c.object { mesh = c.mesh.lathe { profile = profile, segments = 128 },
                       material = c.material.glass { ior = 1.5, fresnel = false, absorption = {0, 0, 0} } })
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = spot })
local technique = c.param("technique", "photon_caustics")
local buffer = c.param("buffer", 0)
local pass = caustics_pass(technique, spot)
if buffer > 0 then pass = c.pass[technique] { light = spot, buffer = buffer } end
g:add("caustics", pass)
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:output("shade.color")
return { scene = scene, graph = g, size = {c.param("size", 128), c.param("size", 128)} }
