-- A glass ball lens over a floor under a directional light (Issue 3's
-- closed-form checks): --set ior=, floor=<height of the floor below the
-- ball's centre>, hide=true, elevation=degrees, fresnel=false (an ideal interface).
local c = require "caustica"
local ior = c.param("ior", 1.5)
local radius = c.param("radius", 0.5)
local floor_depth = c.param("floor", 1.0)      -- distance from the ball's centre down to the floor
local hide = c.param("hide", false)
local elevation = c.param("elevation", 90)
local size = c.param("size", 64)
local aperture = c.param("aperture", 0)
local view = c.param("view", "side")            -- "side", or "down": from just above the floor, looking straight down          -- > 0: an opaque plate above the ball with a square hole of this half-width

local scene = c.scene {
  -- low and from the side, so the floor under the ball is seen past it
  camera = view == "down"
    and c.camera { eye = {0, -floor_depth + c.param("camera_height", 0.08), 0}, target = {0, -floor_depth, 0},
                   up = {0, 0, -1}, fov = 60 }
    or c.camera { eye = {0, -floor_depth + 0.5, 3}, target = {0, -floor_depth, 0}, fov = 20 },
  background = {0, 0, 0},
}
local e = math.rad(elevation)
-- point = H > 0: a point light H above the ball's centre instead of the sun
-- (intensity H^2: the same irradiance at the ball's centre)
local point = c.param("point", 0)
local sun = scene:add(point > 0 and c.light.point { position = {0, point, 0}, intensity = {point * point, point * point, point * point} }
                      or c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = c.param("floor_size", 40) }, position = {0, -floor_depth, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = radius, segments = c.param("segments", 256) },
                                  material = c.material.glass { ior = ior, fresnel = c.param("fresnel", true) } })
ball.visible = not hide
ball.rotation = c.quat.axis_angle({1, 0.3, 0.2}, c.param("turn", 0))  -- a turned ball: the same caustic
if aperture > 0 then
  -- Four slabs around a square hole: only paraxial rays reach the ball.
  local w, plate = 10, c.material.diffuse { color = {0, 0, 0} }
  local y = radius + 0.1
  for _, s in ipairs {
    { pos = {-(w + aperture) / 2, y, 0}, size = {w - aperture, 0.02, 2 * w} },
    { pos = { (w + aperture) / 2, y, 0}, size = {w - aperture, 0.02, 2 * w} },
    { pos = {0, y, -(w + aperture) / 2}, size = {2 * aperture, 0.02, w - aperture} },
    { pos = {0, y,  (w + aperture) / 2}, size = {2 * aperture, 0.02, w - aperture} },
  } do
    scene:add(c.object { mesh = c.mesh.box { size = s.size }, position = s.pos, material = plate })
  end
end
ball.cast_shadows = true
-- mirror = H > 0: a small mirror H above the floor's level, beside the
-- ball's light path (the specular objects' bounding sphere then spans the
-- two: photon_caustics must keep its photons on the ball); mirror_x = its
-- distance to the side (default 0.8)
if c.param("mirror", 0) > 0 then
  local m = scene:add(c.object { mesh = c.mesh.box { size = {0.1, 0.1, 0.1} },
                                 position = {c.param("mirror_x", 0.8), c.param("mirror", 0), 0},
                                 material = c.material.mirror { color = {0.9, 0.9, 0.9} } })
  m.cast_shadows = false
end
local g = c.graph()
if c.param("technique", "") == "iwasaki" then
  -- Iwasaki et al.'s illumination textures (light transport table, virtual planes)
  g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
  g:add("it", c.pass.illumination_textures { light = sun, planes = c.param("planes", 4), size = c.param("texture", 512),
                                             table = c.param("table", 16) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "it.irradiance" })
  if c.param("output", "") == "irradiance" then g:output("it.irradiance") end
elseif c.param("technique", "") == "layered" then
  -- Chaudhari's layered caustics (photons through every interface)
  g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
  g:add("lc", c.pass.layered_caustics { light = sun, buffer = c.param("buffer", 512), layers = c.param("layers", 8),
                                        radius = c.param("radius_px", 2) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "lc.irradiance" })
  if c.param("output", "") == "irradiance" then g:output("lc.irradiance") end
elseif c.param("technique", "") == "beams" then
  -- Liktor & Dachsbacher's beams (surface caustics from the same beams as volume caustics)
  g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
  g:add("beams", c.pass.beam_caustics { light = sun, grid = c.param("grid", 16), refine = c.param("refine", 1), edges = c.param("edges", 0),
                                        blur = c.param("blur", 1.5), max_focus = c.param("max_focus", 1000),
                                        smooth = c.param("smooth", true) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "beams.irradiance" })
  if c.param("output", "") == "irradiance" then g:output("beams.irradiance") end
elseif c.param("techniques", false) then
  -- Hu & Qin's photon caustics on the GPU (the scene's sun is the only light)
  g:add("shadow", c.pass.shadow_map { light = sun, size = 512 })
  g:add("photons", c.pass.photon_caustics { light = sun, buffer = c.param("buffer", 256), texture = c.param("texture", 512),
                                             k = c.param("k", 0),
                                             footprint = c.param("footprint", nil) and tonumber(c.param("footprint", nil)),
                                             pixel_samples = c.param("pixel_samples", nil) and tonumber(c.param("pixel_samples", nil)) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
  if c.param("output", "") == "irradiance" then g:output("photons.irradiance") end
else
  g:add("shade", c.pass.shade {})
end
if c.param("output", "") ~= "irradiance" then g:output("shade.color") end
return { scene = scene, graph = g, size = {size, size} }
