-- Hu & Qin §2.1 refraction (and Wyman's baseline): stability and the
-- paper's claim against the reference.
local t = require "caustica.test"

-- Refraction and reflection of an environment cannot be brighter than the
-- brightest thing in it: the room's ceiling panel, (255, 255, 250) in sRGB,
-- radiance 1.0.
local ENVIRONMENT_MAX = 1.0
local function range_ok(img)
  local s = img:stats()
  return s.nan == 0 and s.max <= ENVIRONMENT_MAX * (1 + 1e-5)
end

for _, method in ipairs { "huqin", "wyman" } do
  t.case(method .. ": IOR 1.0 leaves the environment behind the sphere as it is", function()
    -- Fresnel reflectance is 0 and both refractions keep the direction, so
    -- only Beer-Lambert absorption inside (0.1-0.3 per unit over up to 1.2)
    -- changes the image: compare with absorption-corrected tolerance.
    local with = t.render("tests/scenes/refract.lua", { set = { ior = 1.0, method = method } })
    local without = t.render("tests/scenes/refract.lua", { set = { ior = 1.0, method = method, hide = true } })
    -- absorption at most 1 - exp(-0.3 * 1.2) = 30% of the (sub-1) environment radiance
    t.expect_close(with, without, { rel_rmse = 0.25 })
    t.expect_finite(with)
  end)
end

for _, ior in ipairs { 0.8, 1.33, 2.42 } do
  for _, view in ipairs { "front", "grazing", "near" } do
    t.case(string.format("IOR %g, %s view: no NaN or Inf, within the environment's range", ior, view), function()
      for _, method in ipairs { "huqin", "wyman" } do
        local img = t.render("tests/scenes/refract.lua", { set = { ior = ior, view = view, method = method, iterations = 16 } })
        t.expect(range_ok(img), method .. ": values outside the environment's range or not finite")
      end
    end)
  end
end

t.case("Fig. 11 (IOR 1.75): Hu & Qin's error against the reference is lower than Wyman's", function()
  -- Against each pixel's mean (antialias = true): the pass looks the
  -- environment up over the directions a pixel's rays spread across
  -- (environment_radiance_grad). Issue 8 asked for the error halved: the
  -- pass before issue 8 measures 0.138 against this truth (0.142 against
  -- pixel centres), one lookup per ray at the pixel's centre 0.074 (0.064),
  -- the mean over the pixel 0.054 (0.079: the point-sampled truth keeps the
  -- environment's aliasing).
  local opts = { set = { ior = 1.75 }, size = { 96, 96 } }
  local ref = t.reference("scenes/huqin_sphere.lua", { set = { ior = 1.75 }, size = { 96, 96 }, photons = 0, spp = 64,
                                                       antialias = true })
  opts.set.method = "huqin"
  local hq = t.render("scenes/huqin_sphere.lua", opts)
  opts.set.method = "wyman"
  local wy = t.render("scenes/huqin_sphere.lua", opts)
  local c = require("caustica").image
  local e_hq, e_wy = c.compare(hq, ref).rel_rmse, c.compare(wy, ref).rel_rmse
  t.expect(e_hq < e_wy, string.format("Hu & Qin rel_rmse %.4f, Wyman %.4f", e_hq, e_wy))
  t.expect(e_hq < 0.069, string.format("Hu & Qin rel_rmse %.4f (0.138 before issue 8's changes)", e_hq))
end)

t.case("no isolated pixels on the Fig. 11 sphere at 256^2 (issue 8)", function()
  -- A pixel that differs from all 8 neighbours by more than 0.2 in display
  -- values (sRGB) in some channel: 149 before issue 8, 30 with one
  -- environment lookup per ray at the pixel's centre (thin lines of the
  -- environment squeezed near the rim, picked at every other row), none
  -- with the lookup over the pixel's spread of directions.
  local img = t.render("scenes/huqin_sphere.lua", { size = { 256, 256 } })
  local function display(x)
    x = math.min(math.max(x, 0), 1)
    return x <= 0.0031308 and 12.92 * x or 1.055 * x ^ (1 / 2.4) - 0.055
  end
  local w, h, v = img.width, img.height, {}
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local r, g, b = img:pixel(x, y)
      v[y * w + x] = { display(r), display(g), display(b) }
    end
  end
  local isolated = 0
  for y = 1, h - 2 do
    for x = 1, w - 2 do
      local p, alone = v[y * w + x], true
      for dy = -1, 1 do
        for dx = -1, 1 do
          if alone and (dx ~= 0 or dy ~= 0) then
            local q = v[(y + dy) * w + x + dx]
            if math.max(math.abs(p[1] - q[1]), math.abs(p[2] - q[2]), math.abs(p[3] - q[3])) <= 0.2 then alone = false end
          end
        end
      end
      if alone then isolated = isolated + 1 end
    end
  end
  t.expect(isolated == 0, "isolated pixels: " .. isolated)
end)

t.case("an ideal interface (fresnel = false): Hu & Qin against the reference, no reflection on the sphere", function()
  -- Measured: rel_rmse 0.229 against the reference (0.142 with Fresnel: the
  -- rim, where the ideal interface sends everything into total internal
  -- reflection, is where two interfaces are not enough); 0.118 since the
  -- pass follows total internal reflections (issue 8); the centre, seen
  -- through both interfaces at normal incidence, matches within 1%.
  local opts = { set = { fresnel = false }, size = { 96, 96 } }
  local ref = t.reference("scenes/huqin_sphere.lua", { set = { fresnel = false }, size = { 96, 96 }, photons = 0, spp = 32 })
  local hq = t.render("scenes/huqin_sphere.lua", opts)
  local e = require("caustica").image.compare(hq, ref).rel_rmse
  t.expect(e < 0.14, string.format("rel_rmse %.4f against the reference", e))
  local g, r = hq:pixel(48, 48), ref:pixel(48, 48)
  t.expect(math.abs(g / r - 1) < 0.01, string.format("centre: GPU %.5f, reference %.5f", g, r))
  -- with Fresnel the centre loses 2 x 7.4% (n = 1.75) to reflection and
  -- gains 7.4% of what the front reflects (measured: 0.949 of the ideal
  -- interface's, the reference's 0.941)
  local with = t.render("scenes/huqin_sphere.lua", { size = { 96, 96 } })
  local ref_with = t.reference("scenes/huqin_sphere.lua", { size = { 96, 96 }, photons = 0, spp = 32 })
  local a, b = with:pixel(48, 48), ref_with:pixel(48, 48)
  t.expect(a < 0.97 * g and math.abs(a / b - 1) < 0.02,
           string.format("Fresnel darkens the centre: %.4f, the ideal interface %.4f, the reference %.4f", a, g, b))
end)

t.case("refraction: no refractive object, the image passes through unchanged", function()
  local a = t.render("tests/scenes/refract.lua", { set = { hide = true } })
  local b = t.render("tests/scenes/refract.lua", { set = { hide = true, method = "wyman" } })
  t.expect_close(a, b, { max = 0 })
  t.expect_finite(a)
end)

t.case("Fig. 18: through an IOR 1.0 sphere, the impostor correction removes most of the distortion", function()
  -- The object-free render is the answer (IOR 1.0 bends nothing). Measured
  -- at 256^2: rel_rmse 0.136 through the uncorrected rectangles, 0.054 after
  -- 3 iterations from the §2.2.2 seed (2.5x), 0.048 after 16. The paper
  -- claims at least 2x; so do we.
  local truth = t.render("scenes/huqin_nearby.lua", { set = { hide = true }, size = { 128, 128 } })
  local raw = t.render("scenes/huqin_nearby.lua", { set = { correction = 0 }, size = { 128, 128 } })
  local fixed = t.render("scenes/huqin_nearby.lua", { set = { correction = 3 }, size = { 128, 128 } })
  local img = require("caustica").image
  local e_raw, e_fixed = img.compare(raw, truth).rel_rmse, img.compare(fixed, truth).rel_rmse
  t.expect(e_raw > 2.0 * e_fixed, string.format("uncorrected %.4f, corrected %.4f", e_raw, e_fixed))
end)

t.case("Fig. 24g: recursive reflection and refraction changes what the mirror and the sphere show, finitely", function()
  local flat = t.render("scenes/huqin_fig24.lua", { set = { stage = "g", recursion = 0 }, size = { 96, 96 } })
  local deep = t.render("scenes/huqin_fig24.lua", { set = { stage = "g", recursion = 2 }, size = { 96, 96 } })
  t.expect_finite(deep)
  -- with recursion the teapot reflects the glass sphere (and the sphere
  -- refracts the teapot) instead of the environment behind them
  t.expect_different(flat, deep, 1e-3)
end)

t.case("Fig. 18 against the reference: the impostor correction lowers rel_rmse at least 2x", function()
  -- Convex objects lit from the side, so that the GPU's shading and the
  -- reference agree without the sphere (measured rel_rmse 0.0007): what
  -- remains is the impostors'. Measured at 256^2: 0.104 uncorrected, 0.049
  -- corrected (2.1x).
  local ref = t.reference("scenes/huqin_nearby.lua", { set = { convex = true }, size = { 128, 128 }, photons = 0, spp = 4 })
  local img = require("caustica").image
  local raw = t.render("scenes/huqin_nearby.lua", { set = { convex = true, correction = 0 }, size = { 128, 128 } })
  local fixed = t.render("scenes/huqin_nearby.lua", { set = { convex = true, correction = 3 }, size = { 128, 128 } })
  local e_raw, e_fixed = img.compare(raw, ref).rel_rmse, img.compare(fixed, ref).rel_rmse
  t.expect(e_raw >= 2.0 * e_fixed, string.format("uncorrected %.4f, corrected %.4f", e_raw, e_fixed))
end)

t.case("TIR mask and exit direction: the refraction pass against the reference's exact two-interface trace", function()
  -- The cube of IOR 2.42 at 64 x 64: measured at 128 x 128, the pass marks
  -- 16.8% of the image as meeting total internal reflection and the exact
  -- trace 12.5%, and they agree on 92.5% of the pixels (the pass's d_T and
  -- back-normal lookup are approximations: the mask is where they show).
  local function count(img)
    local covered, tir = 0, 0
    for y = 0, 63 do
      for x = 0, 63 do
        local r, _, _, a = img:pixel(x, y)
        if a > 0.5 then covered = covered + 1 end
        if r > 0.5 then tir = tir + 1 end
      end
    end
    return covered, tir
  end
  local gpu = t.render("tests/scenes/tir_cube.lua", { set = { output = "tir" } })
  local ref = t.reference("tests/scenes/tir_cube.lua", { aov = "tir" })
  local cg, tg = count(gpu)
  local cr, tr = count(ref)
  t.expect(math.abs(cg - cr) <= 0.03 * cr, string.format("the cube covers %d pixels (GPU), %d (reference)", cg, cr))
  t.expect(tr > 0.05 * cr and math.abs(tg - tr) <= 0.5 * tr, string.format("TIR pixels: GPU %d, reference %d", tg, tr))
  local agree = 0
  for y = 0, 63 do
    for x = 0, 63 do
      if (gpu:pixel(x, y) > 0.5) == (ref:pixel(x, y) > 0.5) then agree = agree + 1 end
    end
  end
  t.expect(agree >= 0.88 * 64 * 64, string.format("they agree on %.1f%% of the pixels", 100 * agree / 4096))
  -- IOR 1.0: no total internal reflection anywhere, in either
  local _, none_g = count(t.render("tests/scenes/tir_cube.lua", { set = { output = "tir", ior = 1.0 } }))
  local _, none_r = count(t.reference("tests/scenes/tir_cube.lua", { set = { ior = 1.0 }, aov = "tir" }))
  t.expect(none_g == 0 and none_r == 0, string.format("IOR 1.0: %d and %d TIR pixels", none_g, none_r))
  -- exit directions: unit vectors on the cube, finite everywhere
  local exit = t.render("tests/scenes/tir_cube.lua", { set = { output = "exit" } })
  t.expect_finite(exit)
  local x, y, z, a = exit:pixel(32, 32)
  t.expect(a > 0.5 and math.abs(x * x + y * y + z * z - 1) < 1e-3, "a unit exit direction at the centre")
end)

-- Issue 8: a room (floor, back wall, four boxes; tests/scenes/identity_room.lua).
local c = require "caustica"
local ROOM = "tests/scenes/identity_room.lua"
local function inside_silhouette(img, truth, set)
  local mask = t.render(ROOM, { set = { mask = true, checker = set and set.checker } })
  return c.image.compare(img, truth, mask).rel_rmse
end

t.case("an IOR 1.0 sphere vanishes in a room: the image behind it, whatever shade drew", function()
  -- Measured at 128^2 inside the silhouette: the paper's impostors 0.263
  -- (0.389 uncorrected, 0.252 after 8 corrections: the floor's rectangle
  -- is hit before the wall); the distance map alone 0.072 (what the centre
  -- cannot see: the box tops); the default lookup 0.0004 with shade
  -- drawing the glass (the pass draws what is behind it) and 7e-9 with
  -- shade { specular = false }.
  for _, set in ipairs { {}, { specular = false }, { checker = true }, { lookup = "map" } } do
    local free = t.render(ROOM, { set = { sphere = false, checker = set.checker, specular = set.specular } })
    local e = inside_silhouette(t.render(ROOM, { set = set }), free, set)
    local tol = set.lookup == "map" and 0.1 or 0.03
    t.expect(e < tol, string.format("%s: rel_rmse inside the silhouette %.4f (at most %g)",
                                    set.lookup or (set.checker and "checker wall" or
                                    set.specular == false and "specular = false" or "default"), e, tol))
  end
  local free = t.render(ROOM, { set = { sphere = false } })
  local old = inside_silhouette(t.render(ROOM, { set = { lookup = "impostors" } }), free)
  -- (0.263 when the issue was filed; 0.108 since a hit off the surface its
  -- texel holds is rejected: still no identity)
  t.expect(old > 0.05, string.format("the impostors still fail the identity (%.3f)", old))
end)

t.case("in fog, what every lookup shows through an IOR 1.0 sphere is lit as shade lights it", function()
  -- Issue 50's one lighting function (common/surface_light.glsl): the
  -- surfaces the distance map, the impostors and the scene lookup draw are
  -- lit through the medium, as shade lights the floor seen directly. Before,
  -- they were lit as if there were no fog: 0.685 (scene), 0.694 (map) and
  -- 0.685 (impostors) inside the silhouette; now 0.0004, 0.090 and 0.077,
  -- what each lookup's geometry gives without fog (0.0004, 0.086, 0.080).
  for lookup, tol in pairs { scene = 0.03, map = 0.1, impostors = 0.1 } do
    local free = t.render(ROOM, { set = { sphere = false, fog = true } })
    local e = inside_silhouette(t.render(ROOM, { set = { lookup = lookup, fog = true } }), free)
    t.expect(e < tol, string.format("%s in fog: rel_rmse inside the silhouette %.4f (at most %g)", lookup, e, tol))
  end
end)

t.case("an IOR 1.5 sphere in the room against the reference (its caustics left out)", function()
  -- Inside the silhouette, against 200k x 16 reference photons (their own
  -- noise about 0.09): 0.423 with the impostors and the paper's p_e
  -- decision (rings of wrong exits across the outer half); 0.285 with both
  -- exits tried, the secant iteration and the scene lookup; 0.224 once the
  -- screen-space hit test no longer takes an occluder's edge for a slope;
  -- 0.188 once a surface the camera sees edge-on (a box's side, that the
  -- ray through the ball sees face-on) is asked of the distance map.
  -- Issue 8 asked for half of 0.423.
  local set = { ior = 1.5, shadow = true }
  local ref = t.reference(ROOM, { set = set, photons = 200000, spp = 16, caustics = false })
  local e = inside_silhouette(t.render(ROOM, { set = set }), ref)
  t.expect(e < 0.5 * 0.423, string.format("rel_rmse inside the silhouette %.4f", e))
end)

t.case("no rings of wrong exits: the pass's exit directions on a sphere against the exact trace", function()
  -- The paper's dividing-pixel test (§2.2.1) picked the front surface for
  -- rings of pixels across the outer half of a sphere (P_e quantized to a
  -- pixel where the back surface turns away): their exit directions were
  -- wrong. Counted over the sphere at 128^2, exits more than 10 degrees
  -- from the reference's exact two-interface trace: 34.6% before, 3.7% now
  -- (the outermost pixels, where the grazing entry's d_T is least sure).
  local set = { ior = 1.5, output = "exit" }
  local gpu = t.render(ROOM, { set = set })
  local ref = t.reference(ROOM, { set = set, aov = "exit" })
  local covered, wrong = 0, 0
  for y = 0, 127 do
    for x = 0, 127 do
      local gx, gy, gz, ga = gpu:pixel(x, y)
      local rx, ry, rz, ra = ref:pixel(x, y)
      if ga > 0.5 and ra > 0.5 then
        covered = covered + 1
        if gx * rx + gy * ry + gz * rz < math.cos(math.rad(10)) then wrong = wrong + 1 end
      end
    end
  end
  t.expect(covered > 1000 and wrong <= 0.05 * covered,
           string.format("%d of %d exits more than 10 degrees off (%.1f%%)", wrong, covered, 100 * wrong / covered))
end)

t.case("total internal reflection inside: the IOR 2.42 and 0.8 cubes against the reference", function()
  -- Issue 8's cube (a third of its pixels meet total internal reflection
  -- at the second interface). Over the cube at 128^2 against 128 reference
  -- samples (their own noise 0.047 at 32, 0.02 at 128): the paper's two
  -- interfaces 0.260 (IOR 2.42) and 0.109 (0.8); following total internal
  -- reflections and the Fresnel-reflected part inside (internal = 4, the
  -- default) 0.164 and 0.094 with bilinear normals, 0.067 and 0.082 once
  -- the normal buffers are read without blending across the cube's edges
  -- (surface_normal in refract.frag: the blend made texel-wide bands of
  -- normals belonging to neither face, 95% of the error in 5% of the
  -- pixels); internal = 8: 0.058. Issue 8 asked for < 0.08 at 2.42.
  for ior, tol in pairs { [2.42] = 0.08, [0.8] = 0.09 } do
    local ref = t.reference("tests/scenes/tir_cube.lua", { set = { ior = ior }, photons = 0, spp = 128, size = {128, 128} })
    local mask = t.render("tests/scenes/tir_cube.lua", { set = { ior = ior, method = "layered", output = "info" },
                                                         size = {128, 128} })
    local paper = t.render("tests/scenes/tir_cube.lua", { set = { ior = ior, internal = 1 }, size = {128, 128} })
    local img = t.render("tests/scenes/tir_cube.lua", { set = { ior = ior }, size = {128, 128} })
    t.expect_finite(img)
    local e, ep = c.image.compare(img, ref, mask).rel_rmse, c.image.compare(paper, ref, mask).rel_rmse
    t.expect(e < tol and e < 0.8 * ep, string.format("IOR %g: %.4f (the paper's two interfaces %.4f)", ior, e, ep))
  end
end)

t.case("the camera inside an IOR-1.5 ball: refraction traces the way out as layered_refraction does", function()
  -- Hu & Qin's two interfaces assume the camera outside: with it inside,
  -- the pass drew nothing of the ball. Now each pixel's path starts inside
  -- and meets only the way out; layered_refraction traces every interface
  -- independently, so the two must agree, and differ from the IOR-1.0 view.
  local set = { technique = "refraction", inside = true, ior = 1.5 }
  local img = t.render("tests/scenes/matrix/identity.lua", { set = set })
  t.expect_finite(img)
  set.technique = "layered_refraction"
  local layered = t.render("tests/scenes/matrix/identity.lua", { set = set })
  t.expect_close(img, layered, { rel_rmse = 0.05 }) -- (0.035: a few pixels at the box's edges)
  local unrefracted = t.render("tests/scenes/matrix/identity.lua", { set = { technique = "refraction", inside = true, ior = 1.0 } })
  t.expect_different(img, unrefracted, 0.05)
end)

t.case("the camera inside a glass ball over a floor: with the floor in the input, its shadow and the ball's focus", function()
  -- issue 52: with shade drawing the glass (its default) the input shows
  -- the glass, and refraction shows the floor by its distance map, which
  -- has no caustics (and no shadow unless given the shadow maps: a floor
  -- in a glass ball's shadow would then be black, where the focus lights
  -- it); graph_lint says so. With shade { specular = false } the input
  -- shows the floor, and refraction and layered_refraction both show the
  -- focus in the shadow.
  local function regions(img)
    local cs, cn, cmax, os, on = 0, 0, 0, 0, 0
    for y = 0, 127 do
      for x = 0, 127 do
        local d = math.sqrt((x - 63.5) ^ 2 + (y - 63.5) ^ 2)
        local r, g, b = img:pixel(x, y)
        local l = (r + g + b) / 3
        if d < 20 then
          cs, cn, cmax = cs + l, cn + 1, math.max(cmax, l)
        elseif d > 56 then
          os, on = os + l, on + 1
        end
      end
    end
    return cs / cn, cmax, os / on
  end
  for _, technique in ipairs { "refraction", "layered_refraction" } do
    local img = t.render("tests/scenes/inside_ball.lua", { set = { specular = false, technique = technique } })
    t.expect_finite(img)
    local mean, peak, around = regions(img)
    t.expect(mean < around and peak > 2 * around,
             string.format("%s: the focus in the shadow: centre mean %.3f, peak %.3f, outside %.3f", technique, mean,
                           peak, around))
  end
end)
