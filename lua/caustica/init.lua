-- The scene API (LUA_API.md): the C modules gathered into one table. The
-- constructors are the C functions themselves, so an error in a script
-- points at the script's line, not at this file.
local scene = require "caustica.scene"
local graph = require "caustica.graph"
local image = require "caustica.image"
local host = require "caustica.host"

local c = {}
for k, v in pairs(scene) do c[k] = v end
c.graph = graph.graph
c.pass = graph.pass
c.image = image
c.param = host.param

-- Small helpers for animation scripts.
c.anim = {}

--- Linear interpolation of numbers or {x, y, z} vectors.
function c.anim.lerp(a, b, u)
  if type(a) == "number" then return a + (b - a) * u end
  return { a[1] + (b[1] - a[1]) * u, a[2] + (b[2] - a[2]) * u, a[3] + (b[3] - a[3]) * u }
end

--- A value going 0 -> 1 -> 0 smoothly over `period` seconds.
function c.anim.pingpong(t, period)
  return 0.5 - 0.5 * math.cos(2 * math.pi * t / period)
end

--- A point on a horizontal circle of `radius` at `height`, `turns` per second.
function c.anim.orbit(t, radius, height, turns)
  local a = 2 * math.pi * (turns or 0.1) * t
  return { radius * math.cos(a), height, radius * math.sin(a) }
end

return c
