-- Values that would poison the image (issue 9): NaN, Inf and negative
-- colours are refused at the API with the field's name; legal but
-- degenerate values (eye == target, a zero or parallel up) render finite.
local t = require "caustica.test"
local c = require "caustica"

local nan, inf = 0 / 0, 1 / 0

-- Each row: what is built, and the text its error must contain.
local refused = {
  { "diffuse colour NaN", function() c.material.diffuse { color = { nan, 0, 0 } } end,
    "bad argument 'color' to 'diffuse' (finite numbers >= 0 expected, got nan)" },
  { "diffuse colour negative", function() c.material.diffuse { color = { -1, 0, 0 } } end,
    "bad argument 'color' to 'diffuse' (finite numbers >= 0 expected, got -1)" },
  { "mirror tint Inf", function() c.material.mirror { color = { 1, inf, 1 } } end, "'color' to 'mirror'" },
  { "glass IOR NaN", function() c.material.glass { ior = nan } end, "bad argument 'ior' to 'glass'" },
  { "glass absorption Inf", function() c.material.glass { absorption = { inf, 0, 0 } } end, "'absorption' to 'glass'" },
  { "glass absorption negative", function() c.material.glass { absorption = { 0, -1, 0 } } end, "'absorption' to 'glass'" },
  { "background NaN", function() c.scene { background = { nan, 0, 0 } } end, "bad argument 'background' to 'scene'" },
  { "ambient negative", function() c.scene { ambient = { -0.1, 0, 0 } } end, "bad argument 'ambient' to 'scene'" },
  { "point intensity NaN", function() c.light.point { intensity = { nan, 1, 1 } } end, "'intensity' to 'point'" },
  { "point intensity negative", function() c.light.point { intensity = { -5, 1, 1 } } end, "'intensity' to 'point'" },
  { "point position Inf", function() c.light.point { position = { inf, 1, 1 } } end, "'position' to 'point'" },
  { "directional direction zero", function() c.light.directional { direction = { 0, 0, 0 } } end,
    "'direction' to 'directional' (a non-zero vector expected)" },
  { "spot angle NaN", function() c.light.spot { angle = nan } end, "'angle' to 'spot'" },
  { "spot angle past 90", function() c.light.spot { angle = 120 } end, "'angle' to 'spot'" },
  { "spot softness Inf", function() c.light.spot { softness = inf } end, "'softness' to 'spot'" },
  { "object position NaN", function() c.object { mesh = c.mesh.sphere {}, position = { 0, nan, 0 } } end,
    "bad argument 'position' to 'object' (finite numbers expected, got nan)" },
  { "object scale Inf", function() c.object { mesh = c.mesh.sphere {}, scale = { 1, inf, 1 } } end, "'scale' to 'object'" },
  { "object rotation NaN", function() c.object { mesh = c.mesh.sphere {}, rotation = { nan, 0, 0, 1 } } end,
    "'rotation' to 'object'" },
  { "object rotation zero", function() c.object { mesh = c.mesh.sphere {}, rotation = { 0, 0, 0, 0 } } end,
    "'rotation' to 'object' (a non-zero quaternion expected)" },
  { "sphere radius Inf", function() c.mesh.sphere { radius = inf } end, "'radius' to 'sphere'" },
  { "sphere radius NaN", function() c.mesh.sphere { radius = nan } end, "'radius' to 'sphere'" },
  { "torus tube NaN", function() c.mesh.torus { tube = nan } end, "'tube' to 'torus'" },
  { "box size Inf", function() c.mesh.box { size = { 1, inf, 1 } } end, "'size' to 'box'" },
  { "object position as one number", function() c.object { mesh = c.mesh.sphere {}, position = 0.35 } end,
    "bad argument 'position' to 'object' ({x, y, z} expected, got a single number 0.35)" },
  { "camera eye as one number", function() c.camera { eye = 2.5 } end, "'eye' to 'camera' ({x, y, z} expected" },
  { "camera eye NaN", function() c.camera { eye = { nan, 0, 0 } } end, "bad argument 'eye' to 'camera'" },
  { "camera target Inf", function() c.camera { target = { 0, inf, 0 } } end, "'target' to 'camera'" },
  { "camera up NaN", function() c.camera { up = { 0, nan, 0 } } end, "'up' to 'camera'" },
  { "camera near >= far", function() c.camera { near = 10, far = 5 } end, "near 10 must be less than far 5" },
  { "camera far NaN", function() c.camera { far = nan } end, "'far' to 'camera'" },
  { "camera fov NaN", function() c.camera { fov = nan } end, "'fov' to 'camera'" },
  { "wave amplitude NaN", function() c.deform.wave { amplitude = nan } end, "'amplitude' to 'wave'" },
  { "water attenuation negative", function() c.water { attenuation = { -1, 0, 0 } } end, "'attenuation' to 'water'" },
  { "water size Inf", function() c.water { size = inf } end, "'size' to 'water'" },
  { "medium sigma_s NaN", function() c.medium { sigma_s = { nan, 0, 0 }, box = { { 0, 0, 0 }, { 1, 1, 1 } } } end,
    "'sigma_s' to 'medium'" },
  { "medium g Inf", function() c.medium { g = inf, box = { { 0, 0, 0 }, { 1, 1, 1 } } } end, "'g' to 'medium'" },
  { "shadow bias NaN", function() c.pass.shadow_map { light = c.light.point {}, bias = nan } end,
    "bad argument 'bias' to 'shadow_map' (a finite number expected, got nan)" },
  { "fullscreen uniform NaN", function() c.pass.fullscreen { shader = "x.frag", uniforms = { gain = nan } } end,
    "bad argument 'uniforms' to 'fullscreen' (a finite number expected, got nan)" },
}

for _, row in ipairs(refused) do
  t.case("refused at the API: " .. row[1], function() t.expect_error(row[2], row[3]) end)
end

t.case("a live field refuses NaN too (object.position, light.intensity, camera.near)", function()
  local o = c.object { mesh = c.mesh.sphere {} }
  t.expect_error(function() o.position = { nan, 0, 0 } end, "'position' to 'object'")
  local l = c.light.point {}
  t.expect_error(function() l.intensity = { 1, -1, 1 } end, "'intensity' to 'point'")
  local cam = c.camera { near = 0.1, far = 10 }
  t.expect_error(function() cam.near = 20 end, "near 20 must be less than far 10")
  t.expect(cam.near < cam.far, "a refused assignment leaves the camera as it was")
end)

-- Legal but degenerate: handled without NaN.
for _, view in ipairs { "eye_is_target", "up_zero", "up_parallel" } do
  t.case("a degenerate camera (" .. view .. ") renders finite", function()
    t.expect_finite(t.render("tests/scenes/camera_degenerate.lua", { set = { view = view } }))
  end)
end

t.case("Fresnel: the shaders' fresnel.glsl equals the exact formula (and so core/optics.c, test_optics)", function()
  -- the same exact unpolarised reflectance the C code is checked against in
  -- tests/unit/test_optics.c; here in float on the GPU, 64 cosines x 8 IOR ratios
  local etas = { 1 / 1.5, 1.5, 1 / 2.42, 2.42, 1.0, 0.1, 10.0, 1.0001 }
  local img = t.render("tests/scenes/fresnel_grid.lua")
  t.expect_finite(img)
  local worst = 0
  for y = 0, 7 do
    for x = 0, 63 do
      local cos_i = x / 63
      local r, g = img:pixel(x, 7 - y) -- image rows run down, gl_FragCoord.y up
      local want = t.fresnel(cos_i, etas[y + 1])
      local tir = etas[y + 1] ^ 2 * (1 - cos_i * cos_i) >= 1
      worst = math.max(worst, math.abs(r - want))
      t.expect((g == 1) == tir and (tir or g == 0), string.format("ideal interface at cos %.3f, eta %g: %g", cos_i, etas[y + 1], g))
    end
  end
  -- float arithmetic: 5.5e-5 at most, next to the critical angle where R is steepest
  t.expect(worst < 1e-4, "largest difference from the exact reflectance " .. worst)
end)

t.case("a parameter that must be a multiple (voxels: 128) is refused where the script sets it", function()
  local sun = c.light.directional { direction = {0, -1, 0} }
  for _, name in ipairs { "layered_caustics", "beam_caustics" } do
    t.expect_error(function() c.pass[name] { light = sun, voxels = 200 } end,
                   "bad argument 'voxels' to '" .. name .. "' (a multiple of 128 expected, got 200)")
  end
  t.expect_error(function() c.pass.layered_refraction { color = "shade.color", voxels = 300 } end,
                 "(a multiple of 128 expected, got 300)")
  c.pass.layered_caustics { light = sun, voxels = 384 } -- a multiple is taken
end)
