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
local function aim(g)
  local t = g.centre[2] / -g.light[2]
  g.view_centre = { g.centre[1] + g.light[1] * t, 0, g.centre[3] + g.light[3] * t }
  return g
end
aim(geometry)
-- The same cube in a sun `tilt` degrees off the zenith, from the same side
-- (issue 52 lit it 40 degrees off: photon_caustics left black slivers).
function geometry.tilted(tilt)
  local g = {}
  for k, v in pairs(geometry) do g[k] = v end
  local s = math.tan(math.rad(tilt)) / math.sqrt(0.3 ^ 2 + 0.2 ^ 2)
  g.light = { 0.3 * s, -1, 0.2 * s }
  return aim(g)
end
return geometry
