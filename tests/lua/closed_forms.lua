-- Closed forms of the optics matrix (tests/lua/optics_matrix_test.lua),
-- each derived from the geometry alone, with no renderer in it: a 2D trace
-- of the rays that the case's symmetry reduces it to, binned the way the
-- test reads the image.
local closed = {}

-- Exact unpolarised Fresnel reflectance, eta = n_incident / n_transmitted.
local fresnel = require("caustica.test").fresnel

-- Snell's law in 2D: d (unit) meets a surface with unit normal n facing
-- against it; eta = n_incident / n_transmitted. Returns the refracted unit
-- direction and cos_i, or nil under total internal reflection.
local function refract(dx, dy, nx, ny, eta)
  local cos_i = -(dx * nx + dy * ny)
  local k = 1 - eta * eta * (1 - cos_i * cos_i)
  if k < 0 then return nil end
  local a = eta * cos_i - math.sqrt(k)
  return eta * dx + a * nx, eta * dy + a * ny, cos_i
end

--- Water over a floor: the floor's irradiance per pixel column, by tracing
--- opts.samples rays of a sun `elevation` degrees high (irradiance 1 across
--- its rays, travelling towards +x) through the surface h(x) = amplitude
--- sin(2 pi x / wavelength) into water of IOR `ior` absorbing sigma = {r, g,
--- b} per unit length, onto the floor `depth` below the mean surface, and
--- binning where they land into `columns` equal columns of [x0, x1]. The
--- flux a ray carries is the light through its stretch dx of the surface
--- (-d . (-h', 1) dx), times the Fresnel transmission when `fresnel`.
--- Returns {r = {...}, g = {...}, b = {...}} irradiance per column.
function closed.water_columns(opts)
  local e = math.rad(opts.elevation)
  local dx0, dy0 = math.cos(e), -math.sin(e)
  local A, k = opts.amplitude or 0, 2 * math.pi / (opts.wavelength or 1)
  local n, depth, sigma = opts.ior, opts.depth, opts.sigma
  local cols, x0, x1 = opts.columns, opts.x0, opts.x1
  local width = (x1 - x0) / cols
  local out = { {}, {}, {} }
  for i = 1, cols do out[1][i], out[2][i], out[3][i] = 0, 0, 0 end
  -- the rays that can land in [x0, x1] enter up to depth / tan(elevation) before it, plus the waves' spread
  local from, to = x0 - depth * 2 - 1, x1 + 1
  local samples = opts.samples or 200000
  local step = (to - from) / samples
  for s = 0, samples - 1 do
    local x = from + (s + 0.5) * step
    local h, slope = A * math.sin(k * x), A * k * math.cos(k * x)
    local len = math.sqrt(1 + slope * slope)
    local nx, ny = -slope / len, 1 / len
    local tx, ty, cos_i = refract(dx0, dy0, nx, ny, 1 / n)
    if tx and ty < 0 then
      local flux = -(dx0 * -slope + dy0 * 1) * step
      if opts.fresnel then flux = flux * (1 - fresnel(cos_i, 1 / n)) end
      local t = (h + depth) / -ty
      local land = x + t * tx
      local col = math.floor((land - x0) / width) + 1
      if col >= 1 and col <= cols then
        for c = 1, 3 do
          out[c][col] = out[c][col] + flux * math.exp(-sigma[c] * t) / width
        end
      end
    end
  end
  return out
end

--- A ball lens (radius R, IOR n) in a sun straight above it, the floor F
--- below its centre: the mean irradiance in each of `rings` equal annuli of
--- [0, R] around the axis (the ball's shadow: it gets only the light through
--- the ball). Each ray at distance h from the axis refracts in and out
--- (Fresnel transmissions at both when `fresnel`; the light reflected inside
--- is left out) and carries 2 pi h dh. Returns the means, innermost first.
function closed.ball_rings(opts)
  local R, n, F, rings = opts.radius, opts.ior, opts.floor, opts.rings
  local power = {}
  for i = 1, rings do power[i] = 0 end
  local samples = opts.samples or 200000
  local dh = R / samples
  for s = 0, samples - 1 do
    local h = (s + 0.5) * dh
    local py = math.sqrt(R * R - h * h)
    local px = h
    local t1x, t1y, c1 = refract(0, -1, px / R, py / R, 1 / n)
    local w = 2 * math.pi * h * dh
    if opts.fresnel then w = w * (1 - fresnel(c1, 1 / n)) end
    -- the second crossing of the sphere: p + s t with |p| = R
    local along = -2 * (px * t1x + py * t1y)
    local qx, qy = px + along * t1x, py + along * t1y
    local t2x, t2y, c2 = refract(t1x, t1y, -qx / R, -qy / R, n)
    if t2x and t2y < 0 then
      if opts.fresnel then w = w * (1 - fresnel(c2, n)) end
      local t = (qy + F) / -t2y
      local rho = math.abs(qx + t * t2x)
      local ring = math.floor(rho / R * rings) + 1
      if ring <= rings then power[ring] = power[ring] + w end
    end
  end
  local means = {}
  for i = 1, rings do
    local a, b = (i - 1) / rings * R, i / rings * R
    means[i] = power[i] / (math.pi * (b * b - a * a))
  end
  return means
end

--- The same ball lens: the farthest from the axis that light through it
--- lands on the floor. Near grazing entry the ray turns inward faster than
--- it starts further out, so a band just inside the shadow's outline gets
--- no light at all (0.0047 wide at R = 0.5, IOR 1.0001, floor 1.25 below);
--- the h are taken closer and closer to R to find the fold.
function closed.ball_outermost(opts)
  local R, n, F = opts.radius, opts.ior, opts.floor
  local best = 0
  for k = 1, 400 do
    local h = R * (1 - 10 ^ (-k / 40))
    local py = math.sqrt(R * R - h * h)
    local t1x, t1y = refract(0, -1, h / R, py / R, 1 / n)
    if t1x then
      local along = -2 * (h * t1x + py * t1y)
      local qx, qy = h + along * t1x, py + along * t1y
      local t2x, t2y = refract(t1x, t1y, -qx / R, -qy / R, n)
      if t2x and t2y < 0 then
        best = math.max(best, math.abs(qx + (qy + F) / -t2y * t2x))
      end
    end
  end
  return best
end

-- 3D vectors as {x, y, z}.
local function dot3(a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function normalize3(a)
  local l = math.sqrt(dot3(a, a))
  return { a[1] / l, a[2] / l, a[3] / l }
end

-- Snell's law in 3D (n unit, facing against d), eta = n_incident /
-- n_transmitted: the refracted unit direction, or nil under total internal
-- reflection.
local function refract3(d, n, eta)
  local cos_i = -dot3(d, n)
  local k = 1 - eta * eta * (1 - cos_i * cos_i)
  if k < 0 then return nil end
  local a = eta * cos_i - math.sqrt(k)
  return { eta * d[1] + a * n[1], eta * d[2] + a * n[2], eta * d[3] + a * n[3] }
end

local function reflect3(d, n)
  local k = 2 * dot3(d, n)
  return { d[1] - k * n[1], d[2] - k * n[2], d[3] - k * n[3] }
end

-- The rotation matrix (rows) of `degrees` about `axis` (Rodrigues).
local function rotation(axis, degrees)
  local u = normalize3(axis)
  local a = math.rad(degrees)
  local c, s, t = math.cos(a), math.sin(a), 1 - math.cos(a)
  local x, y, z = u[1], u[2], u[3]
  return { { t * x * x + c, t * x * y - s * z, t * x * z + s * y },
           { t * x * y + s * z, t * y * y + c, t * y * z - s * x },
           { t * x * z - s * y, t * y * z + s * x, t * z * z + c } }
end
closed.refract3 = refract3
local function mul(m, v) return { dot3(m[1], v), dot3(m[2], v), dot3(m[3], v) } end
local function mul_t(m, v)
  return { m[1][1] * v[1] + m[2][1] * v[2] + m[3][1] * v[3], m[1][2] * v[1] + m[2][2] * v[2] + m[3][2] * v[3],
           m[1][3] * v[1] + m[2][3] * v[2] + m[3][3] * v[3] }
end

--- A cube (tests/scenes/matrix/cube_geometry.lua) of IOR `ior` with an
--- ideal interface in a sun of irradiance 1 across its rays: the floor's
--- (y = 0) irradiance from the light that met the cube, binned into the
--- size x size pixels of the orthographic view of the square `view_width`
--- wide around `view_centre` (row j at z = centre - width / 2 + (j + 0.5)
--- width / size). Rays start on a grid `spacing` apart on the plane y = 3
--- and are followed exactly through the cube: refracted at every face,
--- totally reflected where Snell's law has no solution (outside too, at
--- IOR < 1), up to 32 interfaces. Returns grid[j][i] (1-based).
function closed.cube_pixels(geometry, opts)
  local n, size, spacing = opts.ior, opts.size, opts.spacing or 0.004
  local R = rotation(geometry.axis, geometry.angle)
  local C, h = geometry.centre, geometry.side / 2
  local L = normalize3(geometry.light)
  local width, vc = geometry.view_width, geometry.view_centre
  local pixel = width / size
  local grid = {}
  for j = 1, size do grid[j] = {} for i = 1, size do grid[j][i] = 0 end end
  local flux = spacing * spacing * -L[2] -- a horizontal cell's share of the light
  -- the start plane's square that covers the cube's shadow from above
  local reach = h * math.sqrt(3)
  local t0 = (3 - C[2]) / -L[2]
  local sx, sz = C[1] - L[1] * t0, C[3] - L[3] * t0
  local cells = math.floor(2 * reach / spacing)
  for a = 0, cells - 1 do
    for b = 0, cells - 1 do
      local o = { sx - reach + (a + 0.5) * spacing, 3, sz - reach + (b + 0.5) * spacing }
      -- into the cube's frame
      local p = mul_t(R, { o[1] - C[1], o[2] - C[2], o[3] - C[3] })
      local d = mul_t(R, L)
      -- the slab test: where the ray enters the box
      local tin, tout, axis_in = -math.huge, math.huge, 0
      for k = 1, 3 do
        if math.abs(d[k]) < 1e-12 then
          if math.abs(p[k]) > h then tin = math.huge end
        else
          local ta, tb = (-h - p[k]) / d[k], (h - p[k]) / d[k]
          if ta > tb then ta, tb = tb, ta end
          if ta > tin then tin, axis_in = ta, k end
          if tb < tout then tout = tb end
        end
      end
      if tin < tout and tin > 0 then
        local q = { p[1] + d[1] * tin, p[2] + d[2] * tin, p[3] + d[3] * tin }
        local nrm = { 0, 0, 0 }
        nrm[axis_in] = d[axis_in] > 0 and -1 or 1
        local inside = false
        local dir = refract3(d, nrm, 1 / n)
        if dir then inside = true else dir = reflect3(d, nrm) end
        local bounces = 0
        while inside and bounces < 32 do
          -- the face the ray leaves by
          local texit, axis_out = math.huge, 0
          for k = 1, 3 do
            if math.abs(dir[k]) > 1e-12 then
              local tk = ((dir[k] > 0 and h or -h) - q[k]) / dir[k]
              if tk < texit then texit, axis_out = tk, k end
            end
          end
          q = { q[1] + dir[1] * texit, q[2] + dir[2] * texit, q[3] + dir[3] * texit }
          local face = { 0, 0, 0 }
          face[axis_out] = dir[axis_out] > 0 and -1 or 1 -- facing back into the cube, against the ray
          local out = refract3(dir, face, n)
          if out then dir, inside = out, false else dir = reflect3(dir, face) end
          bounces = bounces + 1
        end
        if not inside then
          local wq, wd = mul(R, q), mul(R, dir)
          wq = { wq[1] + C[1], wq[2] + C[2], wq[3] + C[3] }
          if wd[2] < 0 then
            local t = wq[2] / -wd[2]
            local x, z = wq[1] + wd[1] * t, wq[3] + wd[3] * t
            local i = math.floor((x - (vc[1] - width / 2)) / pixel) + 1
            local j = math.floor((z - (vc[3] - width / 2)) / pixel) + 1
            if i >= 1 and i <= size and j >= 1 and j <= size then
              grid[j][i] = grid[j][i] + flux / (pixel * pixel)
            end
          end
        end
      end
    end
  end
  return grid
end

return closed
