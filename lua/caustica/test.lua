-- Scripted regression tests (LUA_API.md):
--   local t = require "caustica.test"
--   t.case("name", function() ... end)
-- `caustica test` runs every *_test.lua file, one line per case, and ends
-- with "N passed, N failed".
local image = require "caustica.image"
local host = require "caustica.host"

local t = { _cases = {}, _results = {} }
local options = host.test_options()
local current -- the case running: {file =, name =, images =}

-- The folder of a path ("." for a bare name).
local function folder_of(path)
  return path:match("^(.*)/[^/]*$") or "."
end

-- A file-name-safe form of a case name.
local function slug(text)
  return (text:gsub("[^%w]+", "_"):gsub("^_+", ""):gsub("_+$", ""):sub(1, 60))
end

-- On a failed image comparison, the rendered image, the golden or other
-- image it was compared with and their difference go to out/ beside the
-- test file, named by the case: <test>.<case>.{new,ref,diff}.png. Returns
-- a sentence naming them.
local function save_failure_images(new, ref)
  if not current then return "" end
  local dir = host.script_dir() .. "/out"
  local ok, err = pcall(host.mkdir, dir)
  if not ok then return " (could not write the images: " .. tostring(err) .. ")" end
  local stem = current.file:match("([^/]*)%.lua$") or "test"
  current.count = (current.count or 0) + 1
  local base = string.format("%s/%s.%s%s", dir, stem, slug(current.name),
                             current.count > 1 and ("." .. current.count) or "")
  local diff, scale = image.difference(new, ref)
  local paths = { new = base .. ".new.png", ref = base .. ".ref.png", diff = base .. ".diff.png" }
  local saved = pcall(function()
    new:save(paths.new)
    ref:save(paths.ref)
    diff:save(paths.diff)
  end)
  if not saved then return " (could not write the images to " .. dir .. ")" end
  current.images = paths
  return string.format("; wrote %s, %s and %s (the difference scaled by %.4g)", paths.new, paths.ref, paths.diff, scale)
end

-- With --report, a passing image case keeps the image it rendered (out/
-- beside the test) for the report's thumbnails.
local function save_thumbnail(img)
  if not (options.report and current) or current.images then return end
  local dir = host.script_dir() .. "/out"
  if not pcall(host.mkdir, dir) then return end
  local stem = current.file:match("([^/]*)%.lua$") or "test"
  local path = string.format("%s/%s.%s.new.png", dir, stem, slug(current.name))
  if pcall(function() img:save(path) end) then current.images = { new = path } end
end

local function fail(message, level)
  error(message, (level or 1) + 1)
end

-- The signatures, checked where a test calls them: a wrong argument is an
-- error at the test's line that names the function, the argument and what
-- it takes (LUA_API.md and TESTING.md list them), not a failure deep in
-- this file. `kind` is a Lua type name, "image" (a caustica.Image) or
-- "image list" (a table of two images).
local function is_image(v)
  return type(v) == "userdata" and getmetatable(v) == "caustica.Image"
end

local function describe(v)
  if is_image(v) then return "an image" end
  return type(v) == "nil" and "nothing" or ("a " .. type(v))
end

local function check(fn, position, name, v, kind, optional)
  if v == nil and optional then return end
  local ok
  if kind == "image" then
    ok = is_image(v)
  elseif kind == "image list" then
    ok = type(v) == "table" and is_image(v[1]) and is_image(v[2])
  else
    ok = type(v) == kind
  end
  if not ok then
    local wanted = kind == "image" and "an image (t.render, t.reference, c.image.load)"
                   or kind == "image list" and "a table of two images ({ref1, ref2})"
                   or ((kind:match("^[aeiou]") and "an " or "a ") .. kind)
    error(string.format("bad argument #%d '%s' to 't.%s' (%s%s expected, got %s)", position, name, fn, wanted,
                        optional and " or nil" or "", describe(v)), 3)
  end
end

--- Registers a test case.
function t.case(name, fn)
  check("case", 1, "name", name, "string")
  check("case", 2, "fn", fn, "function")
  t._cases[#t._cases + 1] = { name = name, fn = fn }
end

--- Renders a scene script and returns its linear image (and per-pass ms).
--- opts: set = {k = v}, size = {w, h}, frame = n
function t.render(script, opts)
  check("render", 1, "script", script, "string")
  check("render", 2, "opts", opts, "table", true)
  -- Called through pcall so that a failure names the test's line, not this file's.
  local ok, img, ms = pcall(image.render, script, opts)
  if not ok then error(img, 2) end
  return img, ms
end


--- Renders the ground truth (the CPU reference) of a scene script.
--- opts: set, size, frame, photons (per iteration), spp (iterations), seed, radius, antialias, tessellated,
--- caustics = false (less the caustic part: what refraction without a caustics pass should match)
function t.reference(script, opts)
  check("reference", 1, "script", script, "string")
  check("reference", 2, "opts", opts, "table", true)
  local ok, img, stats = pcall(image.reference, script, opts)
  if not ok then error(img, 2) end
  return img, stats
end

--- Fails unless `cond` holds.
function t.expect(cond, message)
  check("expect", 2, "message", message, "string", true)
  if not cond then fail(message or "expectation failed", 2) end
end

--- Fails unless a and b are within the given tolerances:
--- { rmse = , max = , psnr = (minimum), rel_rmse = , ssim = (minimum) }
function t.expect_close(a, b, tol)
  check("expect_close", 1, "a", a, "image")
  check("expect_close", 2, "b", b, "image")
  check("expect_close", 3, "tol", tol, "table", true)
  tol = tol or { rmse = 1 / 255 }
  local m = image.compare(a, b)
  local problems = {}
  if m.nan > 0 then problems[#problems + 1] = string.format("%d non-finite values", m.nan) end
  if tol.rmse and m.rmse > tol.rmse then
    problems[#problems + 1] = string.format("rmse %.6g > %.6g", m.rmse, tol.rmse) end
  if tol.rel_rmse and m.rel_rmse > tol.rel_rmse then
    problems[#problems + 1] = string.format("rel_rmse %.6g > %.6g", m.rel_rmse, tol.rel_rmse) end
  if tol.max and m.max > tol.max then
    problems[#problems + 1] = string.format("max %.6g > %.6g", m.max, tol.max) end
  if tol.psnr and m.psnr < tol.psnr then
    problems[#problems + 1] = string.format("psnr %.4g < %.4g", m.psnr, tol.psnr) end
  if tol.ssim and m.ssim < tol.ssim then
    problems[#problems + 1] = string.format("ssim %.4g < %.4g", m.ssim, tol.ssim) end
  if #problems > 0 then
    fail("images differ: " .. table.concat(problems, ", ") .. save_failure_images(a, b), 2)
  end
  save_thumbnail(a)
  return m
end

--- For noisy images (the reference renderer): a per-pixel Z-test, as
--- Mitsuba's render tests do. `refs` is two renders of the truth with
--- different seeds; their mean is the expectation and their difference
--- estimates the variance ((a - b)^2 / 2 per sample, pooled over each
--- pixel's 3x3 neighbourhood so that two samples give a usable estimate).
--- A pixel passes when |img - mean| <= z sqrt(var / 2 + var_floor); the
--- image passes when at least `fraction` of its pixels do.
--- opts: z (3), fraction (0.99), floor (1e-8: the variance of a pixel both
--- renders agree on exactly).
function t.expect_statistically_close(img, refs, opts)
  check("expect_statistically_close", 1, "img", img, "image")
  check("expect_statistically_close", 2, "refs", refs, "image list")
  check("expect_statistically_close", 3, "opts", opts, "table", true)
  opts = opts or {}
  local z, fraction, floor = opts.z or 3, opts.fraction or 0.99, opts.floor or 1e-8
  local a, b = refs[1], refs[2]
  local w, h = img.width, img.height
  if a.width ~= w or b.width ~= w or a.height ~= h or b.height ~= h then
    fail(string.format("image sizes differ: %dx%d against %dx%d and %dx%d", w, h, a.width, a.height, b.width, b.height), 2)
  end
  -- the three images' channels, flattened
  local A, B, I = {}, {}, {}
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local k = (y * w + x) * 3
      A[k + 1], A[k + 2], A[k + 3] = a:pixel(x, y)
      B[k + 1], B[k + 2], B[k + 3] = b:pixel(x, y)
      I[k + 1], I[k + 2], I[k + 3] = img:pixel(x, y)
    end
  end
  local passed, worst = 0, 0
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local ok = true
      for c = 1, 3 do
        local var, n = 0, 0
        for v = math.max(y - 1, 0), math.min(y + 1, h - 1) do
          for u = math.max(x - 1, 0), math.min(x + 1, w - 1) do
            local k = (v * w + u) * 3 + c
            local d = A[k] - B[k]
            var, n = var + d * d / 2, n + 1
          end
        end
        var = var / n
        local k = (y * w + x) * 3 + c
        local score = math.abs(I[k] - 0.5 * (A[k] + B[k])) / math.sqrt(var / 2 + floor)
        if score ~= score or score > z then ok = false end
        if score == score and score > worst then worst = score end
      end
      if ok then passed = passed + 1 end
    end
  end
  local got = passed / (w * h)
  if got < fraction then
    fail(string.format("%.2f%% of pixels within %g standard deviations of the reference (at least %.2f%% needed; "
                       .. "the worst %.3g)", 100 * got, z, 100 * fraction, worst), 2)
  end
  return got
end

--- Fails unless a and b differ by at least `rmse` (a change must show).
function t.expect_different(a, b, rmse)
  check("expect_different", 1, "a", a, "image")
  check("expect_different", 2, "b", b, "image")
  check("expect_different", 3, "rmse", rmse, "number")
  local m = image.compare(a, b)
  if m.rmse < rmse then
    fail(string.format("images should differ: rmse %.6g < %.6g", m.rmse, rmse), 2)
  end
  return m
end

--- Compares with a golden PNG (clamped to [0, 1] as a PNG keeps it) in
--- refs/ beside the test file (tests/refs/ of the project is read too).
--- `caustica test --update-refs` writes the file there instead; a golden
--- image is committed only after a person looked at it. A failure writes
--- the new image, the golden and their difference to out/ beside the test.
function t.expect_golden(img, name, tol)
  check("expect_golden", 1, "img", img, "image")
  check("expect_golden", 2, "name", name, "string")
  check("expect_golden", 3, "tol", tol, "table", true)
  local beside = host.script_dir() .. "/refs/" .. name
  local clamped = img:clamped()
  if options.update_refs then
    local ok, err = pcall(host.mkdir, folder_of(beside))
    if not ok then fail("cannot make " .. folder_of(beside) .. ": " .. tostring(err), 2) end
    clamped:save(beside)
    io.write("  updated ", beside, "\n")
    return
  end
  local path = beside
  local ok, ref = pcall(image.load, path)
  if not ok then
    path = host.root() .. "/tests/refs/" .. name
    ok, ref = pcall(image.load, path)
  end
  if not ok then
    fail("no golden image " .. beside .. " (run caustica test --update-refs, then look at it)", 2)
  end
  local m = image.compare(clamped, ref)
  tol = tol or { rmse = 2 / 255 }
  if m.nan > 0 or (tol.rmse and m.rmse > tol.rmse) or (tol.max and m.max > tol.max) then
    fail(string.format("differs from the golden %s: rmse %.6g (at most %s), max %.6g (at most %s), nan %d%s", path,
                       m.rmse, tostring(tol.rmse or "-"), m.max, tostring(tol.max or "-"), m.nan,
                       save_failure_images(clamped, ref)), 2)
  end
  save_thumbnail(clamped)
  return m
end

--- Fails unless fn raises an error whose message contains `text`.
function t.expect_error(fn, text)
  check("expect_error", 1, "fn", fn, "function")
  check("expect_error", 2, "text", text, "string", true)
  local ok, err = pcall(fn)
  if ok then fail("expected an error" .. (text and (" containing '" .. text .. "'") or ""), 2) end
  if text and not tostring(err):find(text, 1, true) then
    fail("error '" .. tostring(err) .. "' does not contain '" .. text .. "'", 2)
  end
  return err
end

--- Fails unless the image has no NaN or Inf anywhere.
function t.expect_finite(img)
  check("expect_finite", 1, "img", img, "image")
  local s = img:stats()
  if s.nan > 0 then fail(string.format("%d non-finite values", s.nan), 2) end
  return s
end

--- Of the pixels where `mask`'s red is above 0, how many have an RGB
--- relative error against `ref` (|img - ref| / |ref|) below `tol`; returns
--- that count and the masked count.
function t.count_within(img, ref, mask, tol)
  check("count_within", 1, "img", img, "image")
  check("count_within", 2, "ref", ref, "image")
  check("count_within", 3, "mask", mask, "image")
  check("count_within", 4, "tol", tol, "number")
  local w, h = img.width, img.height
  local within, n = 0, 0
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      if mask:pixel(x, y) > 0 then
        local a, b = { img:pixel(x, y) }, { ref:pixel(x, y) }
        local e, s = 0, 0
        for k = 1, 3 do e, s = e + (a[k] - b[k]) ^ 2, s + b[k] ^ 2 end
        n = n + 1
        if math.sqrt(e / s) < tol then within = within + 1 end
      end
    end
  end
  return within, n
end

--- Exact unpolarised Fresnel reflectance, eta = n_incident / n_transmitted
--- (1 under total internal reflection): for tests that derive closed forms.
function t.fresnel(cos_i, eta)
  check("fresnel", 1, "cos_i", cos_i, "number")
  check("fresnel", 2, "eta", eta, "number")
  local sin2_t = eta * eta * (1 - cos_i * cos_i)
  if sin2_t >= 1 then return 1 end
  local cos_t = math.sqrt(1 - sin2_t)
  local rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
  local rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
  return 0.5 * (rs * rs + rp * rp)
end

-- The runner's side (`caustica test`, src/app/cmd_test.c): the file's
-- cases are counted, then each is run by a call of its own, so that
-- --script-timeout and --script-memory hold each case (a case that runs
-- past them fails with the limit's message and the next one runs).

--- How many cases the file registered.
function t._case_count()
  return #t._cases
end

--- Case k's name, or nil when --filter leaves it out.
function t._case_name(k)
  local case = t._cases[k]
  if not case or (options.filter and not case.name:find(options.filter, 1, true)) then return nil end
  return case.name
end

--- Runs case k; prints its line and keeps its result in t._results (for
--- --report and --junit). Returns true when it passed.
function t._run_case(file, k)
  local case = t._cases[k]
  local start = os.clock()
  current = { file = file, name = case.name }
  local ok, err = xpcall(case.fn, function(e) return e end)
  if not ok and err == "not enough memory" and (options.script_memory or 0) > 0 then
    -- the case caught Lua's bare memory error: say which limit it met
    err = string.format("the case used more than %.0f MB of memory (raise --script-memory MB, 0 = no limit)",
                        options.script_memory)
  end
  local seconds = os.clock() - start
  if ok then
    print(string.format("ok   %s: %s (%.2f s)", file, case.name, seconds))
  else
    print(string.format("FAIL %s: %s: %s", file, case.name, tostring(err)))
  end
  t._results[#t._results + 1] = { file = file, name = case.name, ok = ok, message = ok and "" or tostring(err),
                                  seconds = seconds, images = current.images }
  current = nil
  io.stdout:flush()
  return ok
end

return t
