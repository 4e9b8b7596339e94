-- Closed-form floor irradiance for the comparison scenes, from exact 2D
-- traces (the ball by rotational symmetry, the cube and the water because
-- nothing varies along z): each family of parallel rays is traced through
-- every Fresnel branch, and the power between neighbouring rays of the same
-- branch is spread evenly over the floor interval they land on (exact for
-- a mapping that is linear between samples; the samples are dense enough
-- for that to hold to well under 0.1%). The answer is the irradiance at
-- the floor point of each pixel centre (what both renderers sample and
-- converge to: neither filters over the pixel), averaged over square blocks
-- of pixels, the resolution the errors are measured at. The irradiance is
-- read from histogram bins much narrower than a pixel; it is infinite only
-- on the axis below the ball and exactly on a fold, where no pixel centre
-- lies.
local M = {}

local fresnel = require("caustica.test").fresnel
M.fresnel = fresnel

-- 2D refraction of unit (dx, dy) about unit (nx, ny) facing against it.
local function refract(dx, dy, nx, ny, eta)
  local ci = -(dx * nx + dy * ny)
  local s2 = eta * eta * (1 - ci * ci)
  if s2 >= 1 then return nil end
  local ct = math.sqrt(1 - s2)
  return eta * dx + (eta * ci - ct) * nx, eta * dy + (eta * ci - ct) * ny
end

-- A histogram of power over [lo, hi] in `n` bins; deposit(a, b, p) spreads
-- p evenly over [a, b].
local function histogram(lo, hi, n)
  local h = { lo = lo, hi = hi, n = n, width = (hi - lo) / n }
  for i = 1, n do h[i] = 0 end
  function h.deposit(a, b, p)
    if a > b then a, b = b, a end
    if b <= lo or a >= hi or p == 0 then return end
    if b - a < 1e-12 then
      local i = math.floor((a - lo) / h.width) + 1
      if i >= 1 and i <= n then h[i] = h[i] + p end
      return
    end
    local density = p / (b - a)
    local i0 = math.max(1, math.floor((a - lo) / h.width) + 1)
    local i1 = math.min(n, math.floor((b - lo) / h.width) + 1)
    for i = i0, i1 do
      local x0, x1 = lo + (i - 1) * h.width, lo + i * h.width
      local overlap = math.min(b, x1) - math.max(a, x0)
      if overlap > 0 then h[i] = h[i] + density * overlap end
    end
  end
  -- power in [a, b] (partial bins by their fraction)
  function h.power(a, b)
    local sum = 0
    local i0 = math.max(1, math.floor((a - lo) / h.width) + 1)
    local i1 = math.min(n, math.floor((b - lo) / h.width) + 1)
    for i = i0, i1 do
      local x0, x1 = lo + (i - 1) * h.width, lo + i * h.width
      local overlap = math.min(b, x1) - math.max(a, x0)
      if overlap > 0 then sum = sum + h[i] * overlap / h.width end
    end
    return sum
  end
  return h
end

-- Traces the branches of one ray: calls land(key, x, weight) for every
-- branch that reaches the floor y = floor_y; `step(px, py, dx, dy)` gives
-- the next surface hit {t, nx, ny (outward), inside_after?} for the solid.
local function branches(solid, px, py, dx, dy, weight, inside, key, floor_y, land, depth)
  if weight < 1e-7 or depth > 40 then return end
  local hit = solid(px, py, dx, dy, inside)
  if not hit then
    if not inside and dy < 0 then
      if floor_y then
        local t = (floor_y - py) / dy
        land(key, px + t * dx, weight)
      else
        land(key, px, py, dx, dy, weight) -- the ray as it leaves (fog_lens)
      end
    end
    return
  end
  local hx, hy = px + hit.t * dx, py + hit.t * dy
  local nx, ny = hit.nx, hit.ny -- outward
  local n = hit.ior
  local fnx, fny, eta
  if inside then fnx, fny, eta = -nx, -ny, n else fnx, fny, eta = nx, ny, 1 / n end
  local cos_i = -(dx * fnx + dy * fny)
  local f = fresnel(cos_i, eta)
  local rx, ry = dx + 2 * cos_i * fnx, dy + 2 * cos_i * fny
  branches(solid, hx, hy, rx, ry, weight * f, inside, key .. "r" .. hit.face, floor_y, land, depth + 1)
  if f < 1 then
    local tx, ty = refract(dx, dy, fnx, fny, eta)
    if tx then
      branches(solid, hx, hy, tx, ty, weight * (1 - f), not inside, key .. "t" .. hit.face, floor_y, land, depth + 1)
    end
  end
end

-- Runs `samples` rays of a parallel family, ray i given by ray(i) -> px,
-- py, dx, dy, power per unit parameter step; deposits each branch's power
-- between consecutive rays of the same path into the histogram, `radial`
-- rays also weighted by 2 pi b (b = the ray's parameter).
local function trace_family(solid, samples, ray, floor_y, hist, radial, fold)
  local prev = {}
  for i = 0, samples do
    local px, py, dx, dy, param = ray(i)
    local now = {}
    branches(solid, px, py, dx, dy, 1, false, "", floor_y,
      function(key, x, w) now[key] = { x = fold and fold(x) or x, w = w } end, 0)
    if i > 0 then
      for key, b in pairs(now) do
        local a = prev.rays[key]
        if a then
          local w = 0.5 * (a.w * prev.weight + b.w * param.weight)
          hist.deposit(a.x, b.x, w)
        end
      end
    end
    prev = { rays = now, weight = param.weight }
  end
end

-- Block means of the irradiance at the pixel centres, for a camera looking
-- straight down at the floor (square image): the floor point of image
-- point (u, v) in [-1, 1] is (x = cx + u * half, z = -v * half).
local function camera_blocks(size, block, cx, half, irradiance_at)
  local n = size // block
  local out = { n = n, block = block }
  for by = 0, n - 1 do
    for bx = 0, n - 1 do
      local sum = 0
      for y = by * block, by * block + block - 1 do
        for x = bx * block, bx * block + block - 1 do
          local u, v = 2 * (x + 0.5) / size - 1, 1 - 2 * (y + 0.5) / size
          sum = sum + irradiance_at(cx + u * half, -v * half)
        end
      end
      out[by * n + bx + 1] = sum / (block * block)
    end
  end
  return out
end

-- A circle of radius R centred at (0, cy), IOR n, as a solid for branches():
-- the nearest hit ahead, from outside or from inside.
local function circle(R, cy, n)
  return function(px, py, dx, dy, inside)
    local ox, oy = px, py - cy
    local b = ox * dx + oy * dy
    local c = ox * ox + oy * oy - R * R
    local disc = b * b - c
    if disc < 0 then return nil end
    local s = math.sqrt(disc)
    local t = inside and (-b + s) or (-b - s)
    if t <= 1e-9 then
      t = -b + s
      if t <= 1e-9 then return nil end
    end
    return { t = t, nx = (ox + t * dx) / R, ny = (oy + t * dy) / R, ior = n, face = "" }
  end
end

-- The ball lens: R, n, floor `depth` below the centre, vertical sun of
-- irradiance 1; camera `height` above the floor with vertical fov `fov`.
function M.ball_lens(p)
  local R, n, depth = p.radius, p.ior, p.depth
  local half = p.height * math.tan(math.rad(p.fov / 2))
  local rmax = half * math.sqrt(2) * 1.01
  local hist = histogram(0, rmax, p.bins or 40000)
  local solid = circle(R, 0, n)
  local samples = p.samples or 400000
  trace_family(solid, samples, function(i)
    local b = R * i / samples
    return b, R + 1, 0, -1, { weight = 2 * math.pi * b * (R / samples) }
  end, -depth, hist, true, math.abs)
  -- irradiance of each radial bin (power over its ring's area)
  local e = {}
  for i = 1, hist.n do
    local r0, r1 = (i - 1) * hist.width, i * hist.width
    e[i] = hist[i] / (math.pi * (r1 * r1 - r0 * r0))
  end
  return camera_blocks(p.size, p.block, 0, half, function(x, z)
    return e[math.floor(math.sqrt(x * x + z * z) / hist.width) + 1] or 0
  end)
end

-- The cube: side 1 at the origin, IOR n, floor at floor_y, sun `angle`
-- degrees from vertical travelling towards +x; camera at x = cx.
function M.tir_cube(p)
  local n = p.ior
  local a = math.rad(p.angle)
  local dx, dy = math.sin(a), -math.cos(a)
  local half = p.height * math.tan(math.rad(p.fov / 2))
  local hist = histogram(p.cx - half * 1.01, p.cx + half * 1.01, p.bins or 20000)
  local faces = {
    { nx = 1, ny = 0, d = 0.5, name = "R" }, { nx = -1, ny = 0, d = 0.5, name = "L" },
    { nx = 0, ny = 1, d = 0.5, name = "T" }, { nx = 0, ny = -1, d = 0.5, name = "B" },
  }
  local solid = function(px, py, rx, ry, inside)
    -- slab intersection of the square [-0.5, 0.5]^2
    local best
    for _, f in ipairs(faces) do
      local den = f.nx * rx + f.ny * ry
      if (inside and den > 0) or (not inside and den < 0) then
        local t = (f.d - (f.nx * px + f.ny * py)) / den
        if t > 1e-9 then
          local hx, hy = px + t * rx, py + t * ry
          if math.abs(hx) <= 0.5 + 1e-12 and math.abs(hy) <= 0.5 + 1e-12 and (not best or t < best.t) then
            best = { t = t, nx = f.nx, ny = f.ny, ior = n, face = f.name }
          end
        end
      end
    end
    return best
  end
  -- rays across the beam: offset s along the perpendicular (cos a, sin a)
  local span = 0.75 -- covers the square's projection (half-diagonal 0.707)
  local samples = p.samples or 400000
  trace_family(solid, samples, function(i)
    local s = -span + 2 * span * i / samples
    local ox, oy = s * math.cos(a) - 3 * dx, s * math.sin(a) - 3 * dy
    return ox, oy, dx, dy, { weight = 2 * span / samples }
  end, p.floor_y, hist, false)
  return camera_blocks(p.size, p.block, p.cx, half, function(x)
    return hist.power(x - hist.width / 2, x + hist.width / 2) / hist.width
  end)
end

-- Water of IOR n whose surface is y = h(x) (h' its slope), floor at
-- floor_y, vertical sun; camera under water at x = cx (default 0).
function M.water(p)
  local n, h, dh = p.ior, p.height_fn, p.slope_fn
  local half = p.height * math.tan(math.rad(p.fov / 2))
  local cx = p.cx or 0
  local hist = histogram(cx - half * 1.01, cx + half * 1.01, p.bins or 20000)
  local span = half + 0.5 -- the surface that can light the view (refraction bends less than that)
  local samples = p.samples or 400000
  local prev
  for i = 0, samples do
    local x0 = cx - span + 2 * span * i / samples
    local s = dh(x0)
    local norm = math.sqrt(1 + s * s)
    local nx, ny = -s / norm, 1 / norm
    local cos_i = ny -- the ray is (0, -1)
    local w = 1 - fresnel(cos_i, 1 / n)
    local tx, ty = refract(0, -1, nx, ny, 1 / n)
    local x = x0 + tx / -ty * (h(x0) - p.floor_y)
    if prev then hist.deposit(prev.x, x, 0.5 * (prev.w + w) * (2 * span / samples)) end
    prev = { x = x, w = w }
  end
  return camera_blocks(p.size, p.block, cx, half, function(x)
    return hist.power(x - hist.width / 2, x + hist.width / 2) / hist.width
  end)
end

-- The ball lens above a box of fog (fog_lens.lua): single scattering of
-- the sun, direct where the ball does not shadow the fog and focused by
-- the ball (every Fresnel branch leaving it downwards), seen by a camera
-- at `eye` looking along -z. The fluence rate of the focused light is
-- tabulated per height slice and radius (power / |cos| over ring areas,
-- attenuated along each ray's path in the fog); each pixel integrates
-- sigma_s / (4 pi) x fluence x view transmittance along its ray, in steps
-- that shrink near the axis (where the fluence of the axial caustic grows
-- as 1 / r; no pixel's ray meets the axis).
function M.fog_lens(p)
  local R, n, yc = p.radius, p.ior, p.centre
  local ss, st = p.sigma_s, p.sigma_s + p.sigma_a
  local ny, nr, rmax = p.slices or 200, p.bins or 4000, 1.0
  local dr = rmax / nr
  local slices = {}
  for k = 1, ny do
    local h = {}
    for j = 1, nr do h[j] = 0 end
    slices[k] = h
  end
  local solid = circle(R, yc, n)
  local function deposit(h, a, b, w)
    if a > b then a, b = b, a end
    if a >= rmax then return end
    local i0, i1 = math.floor(a / dr) + 1, math.min(nr, math.floor(b / dr) + 1)
    if i0 == i1 or b - a < 1e-12 then h[i0] = h[i0] + w; return end
    local density = w / (b - a)
    for i = i0, i1 do
      local overlap = math.min(b, i * dr) - math.max(a, (i - 1) * dr)
      if overlap > 0 then h[i] = h[i] + density * overlap end
    end
  end
  local samples = p.samples or 20000
  local prev
  for i = 0, samples do
    local b = R * i / samples
    local now = {}
    branches(solid, b, yc + R + 1, 0, -1, 1, false, "", nil,
      function(key, px, py, dx, dy, w) now[key] = { px = px, py = py, dx = dx, dy = dy, w = w } end, 0)
    local weight = 2 * math.pi * b * (R / samples)
    if prev then
      for key, r1 in pairs(now) do
        local r0 = prev.rays[key]
        if r0 then
          local w = 0.5 * (r0.w * prev.weight + r1.w * weight)
          local cos_a = 0.5 * (math.abs(r0.dy) + math.abs(r1.dy))
          for k = 1, ny do
            local y = (k - 0.5) / ny
            local xa = r0.px + r0.dx / r0.dy * (y - r0.py)
            local xb = r1.px + r1.dx / r1.dy * (y - r1.py)
            local atten = math.exp(-st * (1 - y) / cos_a)
            deposit(slices[k], math.abs(xa), math.abs(xb), w * atten / cos_a)
          end
        end
      end
    end
    prev = { rays = now, weight = weight }
  end
  for k = 1, ny do
    local h = slices[k]
    for j = 1, nr do h[j] = h[j] / (math.pi * ((j * dr) ^ 2 - ((j - 1) * dr) ^ 2)) end
  end
  local function fluence(x, y, z)
    local r = math.sqrt(x * x + z * z)
    local direct = r >= R and math.exp(-st * (1 - y)) or 0
    local k = math.min(ny, math.max(1, math.floor(y * ny) + 1))
    local j = math.floor(r / dr) + 1
    return direct + (j <= nr and slices[k][j] or 0)
  end
  local ex, ey, ez = p.eye[1], p.eye[2], p.eye[3]
  local tanh = math.tan(math.rad(p.fov / 2))
  local size, block = p.size, p.block
  local radiance = {}
  for y = 0, size - 1 do
    for x = 0, size - 1 do
      local u, v = (2 * (x + 0.5) / size - 1) * tanh, (1 - 2 * (y + 0.5) / size) * tanh
      local dx, dy, dz = u, v, -1
      local len = math.sqrt(dx * dx + dy * dy + dz * dz)
      dx, dy, dz = dx / len, dy / len, dz / len
      -- the ray's span inside the box [-1,1] x [0,1] x [-1,1]
      local t0, t1 = 0, math.huge
      for _, a in ipairs { { ex, dx, -1, 1 }, { ey, dy, 0, 1 }, { ez, dz, -1, 1 } } do
        if math.abs(a[2]) < 1e-12 then
          if a[1] < a[3] or a[1] > a[4] then t1 = -1 end
        else
          local ta, tb = (a[3] - a[1]) / a[2], (a[4] - a[1]) / a[2]
          if ta > tb then ta, tb = tb, ta end
          t0, t1 = math.max(t0, ta), math.min(t1, tb)
        end
      end
      local L = 0
      local t = t0
      while t < t1 do
        local px, pz = ex + t * dx, ez + t * dz
        local r = math.sqrt(px * px + pz * pz)
        local step = math.min(math.max(0.1 * r, 2e-4), 0.01, t1 - t)
        local tm = t + 0.5 * step
        L = L + ss / (4 * math.pi) * fluence(ex + tm * dx, ey + tm * dy, ez + tm * dz) * math.exp(-st * (tm - t0)) * step
        t = t + step
      end
      radiance[y * size + x + 1] = L
    end
  end
  local nb = size // block
  local out = { n = nb, block = block, radiance = radiance }
  for by = 0, nb - 1 do
    for bx = 0, nb - 1 do
      local sum = 0
      for y = by * block, by * block + block - 1 do
        for x = bx * block, bx * block + block - 1 do sum = sum + radiance[y * size + x + 1] end
      end
      out[by * nb + bx + 1] = sum / (block * block)
    end
  end
  return out
end

return M
