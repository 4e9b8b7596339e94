-- An independent reading of glTF files for the tests of c.gltf.load
-- (tests/lua/gltf_scene_test.lua): its own JSON parser, GLB chunks, float
-- accessors, node matrices and the three samplers of the glTF 2.0
-- specification (Appendix C), none of it shared with the loader under test
-- (src/io/gltf_shim.cpp, src/scene/gltf_pose.c).
local R = {}

-- ---- JSON -----------------------------------------------------------------
local function json_decode(s)
  local pos = 1
  local function ws() pos = s:find("[^ \t\r\n]", pos) or #s + 1 end
  local value
  local function str()
    local out, i = {}, pos + 1
    while true do
      local ch = s:sub(i, i)
      if ch == '"' then pos = i + 1; return table.concat(out) end
      if ch == "\\" then
        local e = s:sub(i + 1, i + 1)
        local map = { n = "\n", t = "\t", r = "\r", b = "\b", f = "\f" }
        if e == "u" then out[#out + 1] = utf8.char(tonumber(s:sub(i + 2, i + 5), 16)); i = i + 6
        else out[#out + 1] = map[e] or e; i = i + 2 end
      else
        out[#out + 1] = ch; i = i + 1
      end
    end
  end
  function value()
    ws()
    local ch = s:sub(pos, pos)
    if ch == "{" then
      local t = {}
      pos = pos + 1; ws()
      if s:sub(pos, pos) == "}" then pos = pos + 1; return t end
      while true do
        ws(); local k = str(); ws(); pos = pos + 1 -- ':'
        t[k] = value(); ws()
        local sep = s:sub(pos, pos); pos = pos + 1
        if sep == "}" then return t end
      end
    elseif ch == "[" then
      local t = {}
      pos = pos + 1; ws()
      if s:sub(pos, pos) == "]" then pos = pos + 1; return t end
      while true do
        t[#t + 1] = value(); ws()
        local sep = s:sub(pos, pos); pos = pos + 1
        if sep == "]" then return t end
      end
    elseif ch == '"' then return str()
    elseif s:sub(pos, pos + 3) == "true" then pos = pos + 4; return true
    elseif s:sub(pos, pos + 4) == "false" then pos = pos + 5; return false
    elseif s:sub(pos, pos + 3) == "null" then pos = pos + 4; return nil
    else
      local num = s:match("^-?[%d.]+[eE]?[-+]?%d*", pos)
      pos = pos + #num
      return tonumber(num)
    end
  end
  return value()
end

local function read_all(path)
  local f = assert(io.open(path, "rb"))
  local d = f:read("a")
  f:close()
  return d
end

--- The file's JSON and its buffers (strings).
function R.open(path)
  local data = read_all(path)
  local gltf, bin
  if data:sub(1, 4) == "glTF" then
    local json_len = string.unpack("<I4", data, 13)
    gltf = json_decode(data:sub(21, 20 + json_len))
    local at = 21 + json_len
    if at < #data then
      local bin_len = string.unpack("<I4", data, at)
      bin = data:sub(at + 8, at + 7 + bin_len)
    end
  else
    gltf = json_decode(data)
  end
  local dir = path:match("^(.*)/") or "."
  local buffers = {}
  for i, b in ipairs(gltf.buffers or {}) do
    if b.uri then buffers[i] = read_all(dir .. "/" .. b.uri) else buffers[i] = bin end
  end
  return { json = gltf, buffers = buffers }
end

local SIZES = { SCALAR = 1, VEC2 = 2, VEC3 = 3, VEC4 = 4, MAT4 = 16 }
local FORMATS = { [5126] = { "<f", 4 }, [5125] = { "<I4", 4 }, [5123] = { "<I2", 2 }, [5121] = { "<I1", 1 },
                  [5122] = { "<i2", 2 }, [5120] = { "<i1", 1 } }
local NORMALISE = { [5121] = 255, [5123] = 65535, [5120] = 127, [5122] = 32767 }

--- Accessor i (0-based) as a list of elements, each a list of numbers.
function R.accessor(file, i)
  local a = file.json.accessors[i + 1]
  local view = file.json.bufferViews[a.bufferView + 1]
  local buf = file.buffers[view.buffer + 1]
  local n = SIZES[a.type]
  local fmt, size = table.unpack(FORMATS[a.componentType])
  local stride = view.byteStride or size * n
  local base = (view.byteOffset or 0) + (a.byteOffset or 0)
  local out = {}
  for e = 0, a.count - 1 do
    local el = {}
    for k = 0, n - 1 do
      local v = string.unpack(fmt, buf, base + e * stride + k * size + 1)
      if a.normalized then v = math.max(v / NORMALISE[a.componentType], -1) end
      el[k + 1] = v
    end
    out[e + 1] = el
  end
  return out
end

-- ---- transforms (column-major 4x4 as flat lists of 16) ----------------------
local function mat_mul(a, b)
  local r = {}
  for c = 0, 3 do
    for row = 0, 3 do
      local s = 0
      for k = 0, 3 do s = s + a[k * 4 + row + 1] * b[c * 4 + k + 1] end
      r[c * 4 + row + 1] = s
    end
  end
  return r
end
R.mat_mul = mat_mul

function R.trs(t, q, s)
  t, q, s = t or { 0, 0, 0 }, q or { 0, 0, 0, 1 }, s or { 1, 1, 1 }
  local x, y, z, w = q[1], q[2], q[3], q[4]
  return {
    (1 - 2 * (y * y + z * z)) * s[1], (2 * (x * y + z * w)) * s[1], (2 * (x * z - y * w)) * s[1], 0,
    (2 * (x * y - z * w)) * s[2], (1 - 2 * (x * x + z * z)) * s[2], (2 * (y * z + x * w)) * s[2], 0,
    (2 * (x * z + y * w)) * s[3], (2 * (y * z - x * w)) * s[3], (1 - 2 * (x * x + y * y)) * s[3], 0,
    t[1], t[2], t[3], 1 }
end

--- Node n's (0-based) world matrix, `override[n]` = {t, r, s} replacing
--- parts of a node's own TRS (an animation's values).
function R.world(file, n, override)
  local parent = {}
  for i, node in ipairs(file.json.nodes) do
    for _, ch in ipairs(node.children or {}) do parent[ch] = i - 1 end
  end
  local function local_matrix(k)
    local node = file.json.nodes[k + 1]
    local o = override and override[k] or {}
    if node.matrix and not (o.t or o.r or o.s) then return node.matrix end
    return R.trs(o.t or node.translation, o.r or node.rotation, o.s or node.scale)
  end
  local m = local_matrix(n)
  local p = parent[n]
  while p do
    m = mat_mul(local_matrix(p), m)
    p = parent[p]
  end
  return m
end

--- A point through a matrix.
function R.apply(m, p)
  return { m[1] * p[1] + m[5] * p[2] + m[9] * p[3] + m[13], m[2] * p[1] + m[6] * p[2] + m[10] * p[3] + m[14],
           m[3] * p[1] + m[7] * p[2] + m[11] * p[3] + m[15] }
end

-- ---- samplers ----------------------------------------------------------------
local function slerp(a, b, u)
  local d = a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4]
  local sign = 1
  if d < 0 then d, sign = -d, -1 end
  local wa, wb = 1 - u, u
  if d < 0.9995 then
    local th = math.acos(d)
    wa, wb = math.sin((1 - u) * th) / math.sin(th), math.sin(u * th) / math.sin(th)
  end
  local q, len = {}, 0
  for k = 1, 4 do q[k] = wa * a[k] + wb * sign * b[k]; len = len + q[k] * q[k] end
  len = math.sqrt(len)
  for k = 1, 4 do q[k] = q[k] / len end
  return q
end

--- Channel `channel` (0-based) of animation `anim` at time t: the value
--- (a list), the target node and its path.
function R.sample(file, anim, channel, t)
  local a = file.json.animations[anim + 1]
  local ch = a.channels[channel + 1]
  local sm = a.samplers[ch.sampler + 1]
  local times = R.accessor(file, sm.input)
  local values = R.accessor(file, sm.output)
  local interp = sm.interpolation or "LINEAR"
  local n = #values[1]
  local flat = {}
  for _, v in ipairs(values) do for _, x in ipairs(v) do flat[#flat + 1] = x end end
  local keys = #times
  local per = #flat / keys / (interp == "CUBICSPLINE" and 3 or 1) -- components a key
  local function key(k, part) -- part 0 in, 1 value, 2 out (cubic); k from 1
    local out = {}
    local base = interp == "CUBICSPLINE" and ((k - 1) * 3 + part) * per or (k - 1) * per
    for c = 1, per do out[c] = flat[base + c] end
    return out
  end
  local vpart = interp == "CUBICSPLINE" and 1 or 0
  local value
  if t <= times[1][1] then value = key(1, vpart)
  elseif t >= times[keys][1] then value = key(keys, vpart)
  else
    local k = 1
    while times[k + 1][1] <= t do k = k + 1 end
    local t0, t1 = times[k][1], times[k + 1][1]
    local u = (t - t0) / (t1 - t0)
    if interp == "STEP" then value = key(k, 0)
    elseif interp == "LINEAR" then
      if ch.target.path == "rotation" then value = slerp(key(k, 0), key(k + 1, 0), u)
      else
        local a0, a1 = key(k, 0), key(k + 1, 0)
        value = {}
        for c = 1, per do value[c] = a0[c] + (a1[c] - a0[c]) * u end
      end
    else
      local td = t1 - t0
      local v0, b0, v1, a1 = key(k, 1), key(k, 2), key(k + 1, 1), key(k + 1, 0)
      local u2, u3 = u * u, u * u * u
      value = {}
      for c = 1, per do
        value[c] = (2 * u3 - 3 * u2 + 1) * v0[c] + (u3 - 2 * u2 + u) * td * b0[c] + (-2 * u3 + 3 * u2) * v1[c]
                   + (u3 - u2) * td * a1[c]
      end
    end
  end
  if ch.target.path == "rotation" then
    local len = math.sqrt(value[1] ^ 2 + value[2] ^ 2 + value[3] ^ 2 + value[4] ^ 2)
    for c = 1, 4 do value[c] = value[c] / len end
  end
  return value, ch.target.node, ch.target.path, n
end

--- Every channel of animation `anim` at t, as overrides for R.world and
--- the weights by node.
function R.pose(file, anim, t)
  local override, weights = {}, {}
  for c = 0, #file.json.animations[anim + 1].channels - 1 do
    local v, node, path = R.sample(file, anim, c, t)
    override[node] = override[node] or {}
    if path == "translation" then override[node].t = v
    elseif path == "rotation" then override[node].r = v
    elseif path == "scale" then override[node].s = v
    else weights[node] = v end
  end
  return override, weights
end

-- ---- skins -------------------------------------------------------------------
--- The triangles (lists of three {x, y, z}) of node `n`'s mesh skinned by
--- its skin at animation `anim`'s time t (glTF 2.0 §3.7.3: per vertex the
--- weighted sum of its joints' world matrix times inverse bind matrix).
function R.skinned_triangles(file, n, anim, t)
  local override = anim and R.pose(file, anim, t) or nil
  local node = file.json.nodes[n + 1]
  local skin = file.json.skins[node.skin + 1]
  local ibm = skin.inverseBindMatrices and R.accessor(file, skin.inverseBindMatrices) or nil
  local joints = {}
  for k, j in ipairs(skin.joints) do
    local inv = ibm and ibm[k] or R.trs()
    joints[k - 1] = mat_mul(R.world(file, j, override), inv)
  end
  local tris = {}
  for _, prim in ipairs(file.json.meshes[node.mesh + 1].primitives) do
    local pos = R.accessor(file, prim.attributes.POSITION)
    local js = R.accessor(file, prim.attributes.JOINTS_0)
    local ws = R.accessor(file, prim.attributes.WEIGHTS_0)
    local skinned = {}
    for v = 1, #pos do
      local sum, q = 0, { 0, 0, 0 }
      for k = 1, 4 do sum = sum + ws[v][k] end
      for k = 1, 4 do
        local w = ws[v][k] / sum
        if w > 0 then
          local p = R.apply(joints[js[v][k]], pos[v])
          q = { q[1] + w * p[1], q[2] + w * p[2], q[3] + w * p[3] }
        end
      end
      skinned[v] = q
    end
    local idx = R.accessor(file, prim.indices)
    for k = 1, #idx, 3 do
      tris[#tris + 1] = { skinned[idx[k][1] + 1], skinned[idx[k + 1][1] + 1], skinned[idx[k + 2][1] + 1] }
    end
  end
  return tris
end

--- The silhouette of `tris` seen down -z through an orthographic camera
--- `width` wide about (cx, cy), size x size pixels: rows of booleans (row 1
--- at the top), pixel centres inside a triangle.
function R.silhouette(tris, cx, cy, width, size)
  local mask = {}
  for y = 1, size do mask[y] = {} end
  local px = width / size
  for _, tri in ipairs(tris) do
    local a, b, c = tri[1], tri[2], tri[3]
    local x0 = math.max(1, math.floor((math.min(a[1], b[1], c[1]) - cx + width / 2) / px))
    local x1 = math.min(size, math.ceil((math.max(a[1], b[1], c[1]) - cx + width / 2) / px) + 1)
    local y0 = math.max(1, math.floor((cy + width / 2 - math.max(a[2], b[2], c[2])) / px))
    local y1 = math.min(size, math.ceil((cy + width / 2 - math.min(a[2], b[2], c[2])) / px) + 1)
    local area = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1])
    if area ~= 0 then
      for y = y0, y1 do
        local wy = cy + width / 2 - (y - 0.5) * px
        for x = x0, x1 do
          local wx = cx - width / 2 + (x - 0.5) * px
          local e0 = ((b[1] - a[1]) * (wy - a[2]) - (b[2] - a[2]) * (wx - a[1])) / area
          local e1 = ((c[1] - b[1]) * (wy - b[2]) - (c[2] - b[2]) * (wx - b[1])) / area
          local e2 = ((a[1] - c[1]) * (wy - c[2]) - (a[2] - c[2]) * (wx - c[1])) / area
          if e0 >= 0 and e1 >= 0 and e2 >= 0 then mask[y][x] = true end
        end
      end
    end
  end
  return mask
end

return R
