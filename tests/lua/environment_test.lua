-- Environments from float data: an equirectangular .pfm / .hdr, and cube
-- faces in .pfm; values above 1 survive, and the GPU and the reference
-- read the same texels.
local t = require "caustica.test"
local c = require "caustica"

local dir = ".caustica-test-env"
os.execute("mkdir -p " .. dir)
local root = io.popen("pwd"):read("*l")

-- radiance of the test sky in direction (x, y, z): red 2 + 2y (4 straight
-- up, above what an 8-bit PNG holds), green 0.25, blue 0.5 + 0.5 x
local function sky(x, y, z) return 2 + 2 * y, 0.25, 0.5 + 0.5 * x end

local function write_pfm(path, w, h, fn)
  local f = assert(io.open(path, "wb"))
  f:write(string.format("PF\n%d %d\n-1.0\n", w, h))
  for row = h - 1, 0, -1 do -- PFM rows go bottom to top
    for col = 0, w - 1 do f:write(string.pack("<fff", fn(col, row))) end
  end
  f:close()
end

-- equirectangular: u = 0.5 + atan2(x, -z) / 2 pi, v = acos(y) / pi
write_pfm(dir .. "/sky.pfm", 256, 128, function(col, row)
  local u, v = (col + 0.5) / 256, (row + 0.5) / 128
  local phi, theta = (u - 0.5) * 2 * math.pi, v * math.pi
  local x, y, z = math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi)
  return sky(x, y, z)
end)

local function centre(img) return img:pixel(16, 16) end

t.case("an equirectangular float environment: seen up, front and right as the formula says, on GPU and reference", function()
  local env = root .. "/" .. dir .. "/sky.pfm"
  for _, v in ipairs { { "up", 0, 1, 0 }, { "front", 0, 0, -1 }, { "right", 1, 0, 0 }, { "down", 0, -1, 0 } } do
    local want = { sky(v[2], v[3], v[4]) }
    local gpu = t.render("tests/scenes/environment_float.lua", { set = { env = env, look = v[1] } })
    local ref = t.reference("tests/scenes/environment_float.lua", { set = { env = env, look = v[1] }, photons = 0, spp = 1 })
    for k = 1, 3 do
      local g, r = select(k, gpu:pixel(16, 16)), select(k, ref:pixel(16, 16))
      -- the GPU's half floats hold 11 bits: 0.1%; the resampling, 2%
      t.expect(math.abs(g - want[k]) <= 0.02 * want[k] + 0.01, string.format("%s channel %d: GPU %.4f, formula %.4f", v[1], k, g, want[k]))
      t.expect(math.abs(g - r) <= 0.002 * math.max(r, 0.1), string.format("%s channel %d: GPU %.5f, reference %.5f", v[1], k, g, r))
    end
  end
end)

t.case("cube faces in .pfm: each face's own value, above 1 kept", function()
  local faces = { px = 1.5, nx = 2.5, py = 3.5, ny = 4.5, pz = 5.5, nz = 6.5 }
  os.execute("mkdir -p " .. dir .. "/faces")
  for name, value in pairs(faces) do
    write_pfm(dir .. "/faces/" .. name .. ".pfm", 8, 8, function() return value, value / 2, 0.125 end)
  end
  local env = root .. "/" .. dir .. "/faces"
  for look, face in pairs { up = "py", down = "ny", front = "nz", right = "px" } do
    local gpu = t.render("tests/scenes/environment_float.lua", { set = { env = env, look = look } })
    local g = centre(gpu)
    t.expect(math.abs(g - faces[face]) < 0.01, string.format("%s: %.4f, face %s holds %.4f", look, g, face, faces[face]))
  end
end)

t.case("a glass ball in the float environment: Hu & Qin against the reference", function()
  local env = root .. "/" .. dir .. "/sky.pfm"
  local gpu = t.render("tests/scenes/environment_float.lua", { set = { env = env, ball = true }, size = { 64, 64 } })
  local ref = t.reference("tests/scenes/environment_float.lua", { set = { env = env, ball = true }, size = { 64, 64 },
                                                                 photons = 0, spp = 16 })
  -- (measured 0.089 at 128 x 128 with 8 iterations: the silhouette's rim
  -- and the reference's own Fresnel noise)
  local e = c.image.compare(gpu, ref).rel_rmse
  t.expect(e < 0.1, string.format("rel_rmse %.4f", e))
  os.execute("rm -rf " .. dir)
end)

t.case("c.environment: one equirectangular .hdr (the procedural sky), the sun where the file puts it", function()
  -- tests/data/make_sky.py: a sun of radiance 400 (plus the sky) 2.5 degrees
  -- wide at (0.45, 0.55, -0.70), a ground of about 0.1 below the horizon
  local sun = t.render("tests/scenes/sky.lua", { set = { look = "sun", fov = 2 } })
  local r = sun:pixel(8, 8)
  t.expect(r > 100, string.format("the sun's radiance %.3g", r))
  local ground = t.render("tests/scenes/sky.lua", { set = { look = "ground" } })
  local g = ground:stats().mean_gray
  t.expect(g > 0.05 and g < 0.2, string.format("the ground's radiance %.3g", g))
  -- the reference reads the same environment
  local ref = t.reference("tests/scenes/sky.lua", { set = { look = "ground" }, photons = 0, spp = 1 })
  t.expect_close(ground, ref, { rel_rmse = 0.02 })
end)
