-- The cube case's geometry, shared by its scene (cube.lua) and its closed
-- form (tests/lua/closed_forms.lua), so the two cannot drift apart.
local geometry = {
  side = 1.0,
  centre = {0, 1.2, 0},
  axis = {1, 0.5, 0.3},
  angle = 35,               -- degrees about axis
  light = {0.3, -1, 0.2},   -- the sun's direction (not unit)
  view_width = 2.4,
}
-- the floor point under the centre along the light
local t = geometry.centre[2] / -geometry.light[2]
geometry.view_centre = { geometry.centre[1] + geometry.light[1] * t, 0, geometry.centre[3] + geometry.light[3] * t }
return geometry
