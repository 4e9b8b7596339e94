-- caustica's reference against POV-Ray 3.7's photon mapping, error
-- against the closed form (closed_form.lua) against wall time, on the same
-- machine in the same sitting. Run from the project root:
--   build/caustica test examples/reference_vs_povray/measure.lua
-- (POV_COUNTS, REF_BUDGETS, REF_SEEDS and SCENES in the environment override the
-- lists below, POV_SPACINGS sets POV-Ray up by photon spacing instead; SIZE and BLOCK the image size, 128, and the error's block,
-- 4: SIZE=512 BLOCK=1 measures per pixel at 512^2; CAUSTICA the binary,
-- build/caustica; the table goes to stdout and to results.md in OUT.)
local t = require "caustica.test"
local c = require "caustica"
local cf = dofile("examples/reference_vs_povray/closed_form.lua")

local dir = "examples/reference_vs_povray"
local out = os.getenv("OUT") or "/tmp/caustica-vs-povray"
os.execute("mkdir -p " .. out)
local size, block = tonumber(os.getenv("SIZE") or 128), tonumber(os.getenv("BLOCK") or 4)
local function list(env, default)
  local s = os.getenv(env)
  if not s then return default end
  local l = {}
  for v in s:gmatch("[^,]+") do l[#l + 1] = tonumber(v) or v end
  return l
end
local pov_counts = list("POV_COUNTS", { 30000, 100000, 300000, 1000000 })
local ref_budgets = list("REF_BUDGETS", { 1, 2, 4, 8 })
-- REF_SEEDS=1,2,3: the reference at each budget once per seed (its error swings between seeds)
local ref_seeds = list("REF_SEEDS", { 1 })
-- REF_BY_ITERATIONS=1: REF_BUDGETS are iterations (--spp), not seconds: equal work, whatever the machine's pace
local by_iterations = os.getenv("REF_BY_ITERATIONS") == "1"
-- POV_SPACINGS=0.008,0.004: POV-Ray's photons by spacing, gathered as issue 53 sets it up, instead of counts
local pov_spacings = os.getenv("POV_SPACINGS") and list("POV_SPACINGS", {})

-- POV-Ray's isotropic media scattering has phase function 1 where
-- caustica's (and physics') has 1 / (4 pi): its media radiance is 4 pi
-- times larger (measured on the lit fog box without the ball: 12.7).
POV_MEDIA = 1 / (4 * math.pi)

local function fresnel_t(deg, n) return 1 - cf.fresnel(math.cos(math.rad(deg)), 1 / n) end
-- The ball lens at three floor depths: before its paraxial focus (the
-- marginal rays' cusp, seen from closer so the camera stays below the
-- ball), at it, and beyond it. `file` names the twin scene files, `set` the
-- parameters both read (--set for caustica, Declare for POV-Ray).
local function ball(depth, height)
  return { file = "ball_lens", set = { depth = depth, height = height }, truth = function()
    return cf.ball_lens { radius = 0.5, ior = 1.5, depth = depth, height = height, fov = 60, size = size, block = block }
  end }
end
local scenes = {
  ball_lens = ball(0.75, 0.2),
  ball_lens_before = ball(0.65, 0.1),
  ball_lens_beyond = ball(1.0, 0.2),
  -- issue 53's floors, in radii below the centre: 1.25 R (before the focus) and 2.5 R (beyond it)
  ball_lens_125R = ball(0.625, 0.1),
  ball_lens_250R = ball(1.25, 0.2),
  tir_cube = function()
    return cf.tir_cube { ior = 2.42, angle = 30, floor_y = -1.0, height = 0.4, cx = 0.25, fov = 90, size = size,
                         block = block }
  end,
  flat_water = function()
    local e = math.cos(math.rad(30)) * fresnel_t(30, 1.33)
    local b = { n = size // block }
    for i = 1, b.n * b.n do b[i] = e end
    return b
  end,
  fog_lens = function()
    -- radiance directly (not irradiance): the block errors compare radiance
    local b = cf.fog_lens { radius = 0.4, ior = 1.5, centre = 1.45, sigma_s = 0.5, sigma_a = 0.1, eye = { 0, 0.5, 3 },
                            fov = 20, size = size, block = block }
    b.radiance_units = true
    return b
  end,
  sine_water = function()
    local A, L = 0.06, 0.5
    return cf.water { ior = 1.33, floor_y = -0.5, height = 0.3, fov = 40, size = size, block = block, cx = 0.000853,
                      height_fn = function(x) return A * math.cos(2 * math.pi * x / L) end,
                      slope_fn = function(x) return -A * 2 * math.pi / L * math.sin(2 * math.pi * x / L) end }
  end,
}
local order = list("SCENES", { "ball_lens", "tir_cube", "flat_water", "sine_water", "fog_lens" })
local function scene_of(name)
  local s = scenes[name]
  if type(s) == "function" then return { file = name, set = {}, truth = s } end
  return s
end
local function settings_for(s, pov)
  local l = {}
  for k, v in pairs(s.set) do
    l[#l + 1] = pov and string.format(" Declare=%s=%g", k:sub(1, 1):upper() .. k:sub(2), v)
      or string.format(" --set %s=%g", k, v)
  end
  table.sort(l)
  return table.concat(l)
end

-- relative RMS error of the block means of `img` (scaled by `scale` into
-- irradiance) against the closed form's
local function block_error(img, truth, scale)
  local n, num, den = truth.n, 0, 0
  for by = 0, n - 1 do
    for bx = 0, n - 1 do
      local sum = 0
      for y = by * block, by * block + block - 1 do
        for x = bx * block, bx * block + block - 1 do
          local r, g, b = img:pixel(x, y)
          sum = sum + (r + g + b) / 3
        end
      end
      local est = scale * sum / (block * block)
      local want = truth[by * n + bx + 1]
      num = num + (est - want) ^ 2
      den = den + want * want
    end
  end
  return math.sqrt(num / den)
end

-- the closed form's block means as a PFM image (radiance, albedo 1), to look at
local function save_truth(truth, path)
  local f = io.open(path, "wb")
  local n = truth.n
  f:write(string.format("PF\n%d %d\n-1.0\n", n, n))
  for by = n - 1, 0, -1 do
    for bx = 0, n - 1 do
      local v = truth[by * n + bx + 1] / (truth.radiance_units and 1 or math.pi)
      f:write(string.pack("<fff", v, v, v))
    end
  end
  f:close()
end

local function timed(cmd)
  local p = io.popen("s=$(date +%s.%N); " .. cmd .. " >/dev/null 2>&1; rc=$?; e=$(date +%s.%N); echo $rc $s $e")
  local rc, s, e = p:read("*a"):match("(%d+) (%S+) (%S+)")
  p:close()
  return tonumber(rc), tonumber(e) - tonumber(s)
end

local lines = { "| scene | renderer | setting | seconds | error |", "|---|---|---|---|---|" }
local function row(...) lines[#lines + 1] = "| " .. table.concat({ ... }, " | ") .. " |"; print(lines[#lines]) end

t.case("caustica reference vs POV-Ray on closed-form scenes", function()
  for _, name in ipairs(order) do
    local sc = scene_of(name)
    local truth = sc.truth()
    save_truth(truth, string.format("%s/%s_closed_form.pfm", out, name))
    -- POV-Ray: photon counts (its photon shooting is single-threaded, the
    -- trace uses both cores: +WT2); it reports radiance = irradiance x
    -- albedo (no 1/pi), caustica albedo / pi x irradiance.
    local settings = {}
    for _, count in ipairs(pov_counts) do settings[#settings + 1] = { count = count, samples = 10 } end
    if pov_spacings then
      -- photon mapping set up for a consistent estimate (issue 53): K photons a gather growing as the
      -- square root of the photon count (100 at a spacing of 0.008, 400 at 0.002), the gather radius
      -- 1.2 spacing sqrt(K / pi)
      -- (POV_SPACING_SCALE: the spacings are a unit-radius scene's, scaled into this one's: 0.5 for the
      -- ball lens of radius 0.5)
      settings = {}
      local scale = tonumber(os.getenv("POV_SPACING_SCALE") or 1)
      for _, spacing in ipairs(pov_spacings) do
        local k = math.floor(100 * 0.008 / spacing + 0.5)
        settings[#settings + 1] = { spacing = spacing * scale, gather = k,
                                    radius = 1.2 * spacing * scale * math.sqrt(k / math.pi), samples = 10 }
      end
    end
    if name == "fog_lens" and not os.getenv("POV_COUNTS") then
      -- media: photons and samples along each ray both set its quality
      settings = { { count = 30000, samples = 10 }, { count = 100000, samples = 20 }, { count = 300000, samples = 50 } }
      -- (at 512^2 the last takes POV-Ray minutes: its media samples grow with the pixels)
      if size > 256 then settings[3] = nil end
    end
    for _, set in ipairs(settings) do
      local count = set.count
      local photons = set.spacing and string.format("Declare=Spacing=%g Declare=Gather=%d Declare=Radius=%.5f",
                                                    set.spacing, set.gather, set.radius)
                      or string.format("Declare=Count=%d", count)
      local label = set.spacing and string.format("spacing %g, gather 20, %d, radius %.4f", set.spacing, set.gather,
                                                  set.radius)
                    or "count " .. count
      local file = string.format("%s/%s_pov_%s.hdr", out, name, set.spacing and ("s" .. set.spacing) or count)
      local rc, secs = timed(string.format(
        "povray -D +I%s/%s.pov +O%s +FH +W%d +H%d +WT2 -A %s Declare=Samples=%d%s",
        dir, sc.file, file, size, size, photons, set.samples, settings_for(sc, true)))
      t.expect(rc == 0, "povray failed on " .. name)
      row(name, "POV-Ray 3.7", label .. (name == "fog_lens" and (", samples " .. set.samples) or ""),
        string.format("%.2f", secs),
        string.format("%.2f%%", 100 * block_error(c.image.load(file), truth, truth.radiance_units and POV_MEDIA or 1)))
    end
    local budgets = ref_budgets
    if name == "fog_lens" and not os.getenv("REF_BUDGETS") then budgets = { 2, 4, 8, 16 } end
    for _, budget in ipairs(budgets) do
      for _, seed in ipairs(ref_seeds) do
        local file = string.format("%s/%s_ref_%g_%d.hdr", out, name, budget, seed)
        local rc, secs = timed(string.format(
          "%s reference %s/%s.lua -o %s --size %dx%d %s %g --photons %d --seed %d%s",
          os.getenv("CAUSTICA") or "build/caustica", dir, sc.file, file, size, size,
          by_iterations and "--spp" or "--time-budget", budget,
          tonumber(os.getenv("REF_PHOTONS") or 200000), seed, settings_for(sc, false)))
        t.expect(rc == 0, "caustica reference failed on " .. name)
        row(name, "caustica reference", (by_iterations and (budget .. " iterations") or ("budget " .. budget .. " s"))
          .. (#ref_seeds > 1 and (", seed " .. seed) or ""),
          string.format("%.2f", secs),
          string.format("%.2f%%", 100 * block_error(c.image.load(file), truth, truth.radiance_units and 1 or math.pi)))
      end
    end
  end
  local f = io.open(out .. "/results.md", "w")
  f:write(table.concat(lines, "\n"), "\n")
  f:close()
end)
