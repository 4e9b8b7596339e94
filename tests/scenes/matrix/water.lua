-- Optics matrix: water over a floor in the sun, seen straight down (issue 27).
-- A sun `elevation` degrees high, water of IOR 1.33 absorbing {0.2, 0.5, 1.0}
-- per unit length, the floor `depth` below its mean surface. The surface is
-- flat, or ridges h(x) = amplitude sin(2 pi x / wavelength) (uniform along z).
-- The camera sees exactly the floor's x in [-0.5, 0.5] (orthographic, or
-- perspective from 1 above the surface); with ortho = true its pixel centres
-- lie on the water grid's lines (the grid's spacing is half a pixel), the
-- case where a fill rule that depends on the rasterizer drops whole rows.
-- The output is the caustics pass's irradiance on the floor.
-- --set technique=NAME (cv_resolution= caustic_volumes' generator grid), ortho=true|false, fresnel=true|false, amplitude=, wavelength=, elevation=, depth=,
--       extent= (the water's and the floor's width, 6; the view stays 1 wide), fov= (a perspective
--       camera's, wider than the floor's [-0.5, 0.5]: flat water only), scale= (the whole case
--       scaled by it, absorption by 1 / scale: the floor's light unchanged)
local c = require "caustica"
local caustics_pass = require "caustics_pass"
local k = c.param("scale", 1.0)
local depth = c.param("depth", 2.0)
local e = math.rad(c.param("elevation", 60))
local size = c.param("size", 64)
local eye = {0, k, 0}
local scene = c.scene {
  camera = c.param("ortho", true)
    and c.camera { eye = eye, target = {0, -depth * k, 0}, up = {0, 0, -1}, ortho = { width = k },
                   near = 0.05 * k, far = 100 * k }
    or c.camera { eye = eye, target = {0, -depth * k, 0}, up = {0, 0, -1},
                  fov = c.param("fov", 2 * math.deg(math.atan(0.5 / (1 + depth)))), near = 0.05 * k, far = 100 * k },
  background = {0, 0, 0},
}
local sun = scene:add(c.light.directional { direction = {math.cos(e), -math.sin(e), 0}, intensity = {1, 1, 1} })
local extent = c.param("extent", 6)
scene:add(c.object { mesh = c.mesh.plane { size = extent * k }, position = {0, -depth * k, 0},
                     material = c.material.diffuse { color = {1, 1, 1} } })
-- 2 cells per pixel of a 64-pixel view, offset so that the lines fall on its
-- pixel centres (coarser on water wider than 8, where the lines no longer fall on them)
local cells = math.min(extent * 2 * 64, 1024)
local water = scene:add(c.water { size = extent * k, resolution = cells + 1, depth = depth * k, ior = 1.33,
                                  position = {0.5 / 64 * k, 0, 0.5 / 64 * k},
                                  attenuation = {0.2 / k, 0.5 / k, 1.0 / k}, fresnel = c.param("fresnel", false) })
local amplitude, wavelength = c.param("amplitude", 0), c.param("wavelength", 1.0)
if amplitude > 0 then
  water:set_heights(function(x, z) return amplitude * k * math.sin(2 * math.pi * x / (wavelength * k)) end)
end
local g = c.graph()
g:add("caustics", caustics_pass(c.param("technique", "photon_caustics"), sun, water))
g:output("caustics.irradiance")
return { scene = scene, graph = g, size = {size, size} }
