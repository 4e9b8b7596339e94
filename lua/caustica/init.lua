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
c.techniques = graph.techniques
c.image = image
c.param = host.param
c.asset = host.asset
-- c.gltf.open (C: the file as values) and c.gltf.load (Lua: objects,
-- cameras, lights and animations made of them)
c.gltf.load = require("caustica.gltf").loader(c)

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

-- A name the API does not have is an error that lists the ones it has
-- (`c.mesh.cylindr` would otherwise be "attempt to call a nil value"); the
-- level-2 error points at the script's line.
local function known_names(t, what)
  local mt = getmetatable(t) or {}   -- c.texture keeps its __call
  mt.__index = function(_, name)
    local known = {}
    for k in pairs(t) do known[#known + 1] = tostring(k) end
    table.sort(known)
    local near = host.suggest(tostring(name), known)
    error(string.format("unknown %s '%s'%s (known: %s)", what, tostring(name),
                        near and string.format(" (did you mean '%s'?)", near) or "",
                        table.concat(known, ", ")), 2)
  end
  setmetatable(t, mt)
end
known_names(c.mesh, "mesh")
known_names(c.material, "material")
known_names(c.light, "light")
known_names(c.texture, "texture")
known_names(c.deform, "deformer")
known_names(c.anim, "c.anim function")
known_names(c.gltf, "c.gltf function")
known_names(c, "c field")

return c
