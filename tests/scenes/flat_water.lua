-- A flat water surface over a floor under a directional light, seen by a
-- camera under water looking straight down (Issue 3's closed form):
-- --set depth=, elevation=degrees, ior=, camera_height=, light=directional|point|spot,
-- fresnel=false (an ideal interface), rect=true (the water and the floor
-- 3 x 1.5 instead of 3 x 3), technique=photons (photon_caustics instead of
-- caustic_volumes; buffer=, texture=, k=, footprint=)
local c = require "caustica"
local depth = c.param("depth", 0.5)
local elevation = c.param("elevation", 60)
local ior = c.param("ior", 1.33)
local camera_height = c.param("camera_height", 0.3)    -- above the floor, under the surface
local size = c.param("size", 64)
local e = math.rad(elevation)

local scene = c.scene {
  -- ortho = W: an orthographic camera W wide looking straight down (every pixel the same floor area)
  camera = c.param("ortho", 0) > 0
    and c.camera { eye = {0, -depth + camera_height, 0}, target = {0, -depth, 0}, up = {0, 0, -1},
                   ortho = { width = c.param("ortho", 0) } }
    or c.camera { eye = {0, -depth + camera_height, 0}, target = {0, -depth, 0}, up = {0, 0, -1}, fov = 40 },
  background = {0, 0, 0},
}
local sun
if c.param("light", "directional") == "point" then
  sun = scene:add(c.light.point { position = {0.5, 2.0, 0.2}, intensity = {4, 4, 4} })
elseif c.param("light", "directional") == "spot" then
  -- a cone (angle = its half-angle) whose fully lit core covers the floor the camera sees
  sun = scene:add(c.light.spot { position = {0.5, 2.0, 0.2}, direction = {-0.5, -2.5, -0.2}, angle = 40,
                                 softness = 0.2, intensity = {4, 4, 4} })
else
  sun = scene:add(c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
end
local extent = c.param("rect", false) and {3, 1.5} or 3
scene:add(c.object { mesh = c.mesh.plane { size = extent }, position = {0, -depth, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
local absorb = c.param("absorb", true)    -- false: clear water (what the bench compares: the GPU shading
                                          -- here does not absorb along the under-water view path)
local water = scene:add(c.water { size = extent, resolution = c.param("grid", 9), depth = depth, ior = ior,
                                  attenuation = absorb and {0.2, 0.5, 1.0} or {0, 0, 0},
                                  fresnel = c.param("fresnel", true) })
local wave = c.param("wave", 0.0)          -- amplitude of a sinusoidal surface (0: flat)
local wavelength = c.param("wavelength", 0.75)
local shape = c.param("shape", "waves")     -- "waves" (2D), "ridges" (along x only), "spikes" (every other vertex)
if shape == "spikes" then
  local n, step = c.param("grid", 9), 3 / (c.param("grid", 9) - 1)
  water:set_heights(function(x, z)
    local i, j = math.floor((x + 1.5) / step + 0.5), math.floor((z + 1.5) / step + 0.5)
    return ((i + j) % 2) * wave
  end)
elseif wave > 0 then
  water:set_heights(function(x, z)
    if shape == "ridges" then return wave * math.sin(2 * math.pi * x / wavelength) end
    return wave * math.sin(2 * math.pi * x / wavelength) * math.cos(2 * math.pi * z / 1.1)
  end)
end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 1024 })
if c.param("light", "directional") == "spot" then
  -- (caustic volumes take directional and point lights; the spot is for the reference)
  g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = false })
elseif c.param("technique", "volumes") == "photons" then
  -- Hu & Qin's photons through the water's one interface (issue 8's moire test)
  g:add("cv", c.pass.photon_caustics { light = sun, buffer = c.param("buffer", 256), texture = c.param("texture", 512),
                                       k = c.param("k", 0),
                                       footprint = c.param("footprint", nil) and tonumber(c.param("footprint", nil)) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "cv.irradiance", specular = false })
else
  g:add("cv", c.pass.caustic_volumes { light = sun, water = water, resolution = c.param("generator", 0) })
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "cv.irradiance", specular = false })
end
g:output("shade.color")
return { scene = scene, graph = g, size = {size, size} }
