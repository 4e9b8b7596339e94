-- Closed forms of the optics matrix (tests/lua/optics_matrix_test.lua),
-- each derived from the geometry alone, with no renderer in it: a 2D trace
-- of the rays that the case's symmetry reduces it to, binned the way the
-- test reads the image.
local closed = {}

-- Exact unpolarised Fresnel reflectance, eta = n_incident / n_transmitted.
local function fresnel(cos_i, eta)
  local sin2_t = eta * eta * (1 - cos_i * cos_i)
  if sin2_t >= 1 then return 1 end
  local cos_t = math.sqrt(1 - sin2_t)
  local rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
  local rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
  return 0.5 * (rs * rs + rp * rp)
end
closed.fresnel = fresnel

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

return closed
