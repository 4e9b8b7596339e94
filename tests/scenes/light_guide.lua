-- A light guide: a glass rod 6 long and 0.04 square along -z, seen into its
-- near end 25 degrees off its axis, in a uniform white background. With an
-- ideal interface (fresnel = false) the light refracts into the end face,
-- meets each side beyond the critical angle (a ray inside is within 41.8
-- degrees of the axis, so it meets a side at 48.2 degrees or more) and
-- leaves the far end as it entered: the end face shows the background
-- exactly, after about 90 total internal reflections. --set length=200:
-- a rod of about 3,000, past the reference's cap, which it says.
local c = require "caustica"
local angle = math.rad(25)
local d = 0.35
local scene = c.scene {
  camera = c.camera { eye = {d * math.sin(angle), 0.004, d * math.cos(angle)}, target = {0, 0, 0}, fov = 10 },
  background = {1, 1, 1},
  ambient = {0, 0, 0},
}
local length = c.param("length", 6)
scene:add(c.object { mesh = c.mesh.box { size = {0.04, 0.04, length} }, position = {0, 0, -length / 2},
                     material = c.material.glass { ior = 1.5, fresnel = false } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {64, 64} }
