-- Emissive surfaces: c.material.emissive and glTF emissiveFactor (x
-- KHR_materials_emissive_strength), seen directly and through glass, on the
-- GPU and in the reference alike; they light nothing.
local t = require "caustica.test"
local c = require "caustica"

local function near(a, b, tol) return math.abs(a - b) <= tol * math.max(math.abs(b), 1e-6) end

for _, case in ipairs { { gltf = false, e = { 2, 1, 0.5 } }, { gltf = true, e = { 4, 2, 1 } } } do
  local what = case.gltf and "glTF emissiveFactor x emissive_strength" or "c.material.emissive"
  t.case(what .. ": seen directly it is its emission; through the ball the GPU matches the reference", function()
    local set = { gltf = case.gltf }
    local gpu = t.render("tests/scenes/emissive.lua", { set = set })
    local ref = t.reference("tests/scenes/emissive.lua", { set = set, photons = 0, spp = 16 })
    for k = 1, 3 do
      t.expect(near(select(k, gpu:pixel(4, 4)), case.e[k], 1e-3), string.format("GPU channel %d: %g", k, select(k, gpu:pixel(4, 4))))
      t.expect(near(select(k, ref:pixel(4, 4)), case.e[k], 1e-6), string.format("reference channel %d: %g", k, select(k, ref:pixel(4, 4))))
    end
    -- the stripe in front of the panel gets no light from it (no interreflection)
    local sx = 41 -- x = 0.4 (0.25 to 0.55) at z = -0.95, 3.95 from the eye, fov 40: pixels 38 to 44
    t.expect(gpu:pixel(sx, 4) < 1e-4 and ref:pixel(sx, 4) < 1e-4, "the stripe stays dark: " .. gpu:pixel(sx, 4))
    -- through both interfaces at normal incidence: T^2 = 0.9216 of the panel
    local g, r = gpu:pixel(32, 32), ref:pixel(32, 32)
    t.expect(near(g, r, 0.05), string.format("ball centre: GPU %.4f, reference %.4f", g, r))
    t.expect(near(r, 0.9216 * case.e[1], 0.05), string.format("reference %.4f, T^2 x emission %.4f", r, 0.9216 * case.e[1]))
    -- measured 0.115 at 128 x 128: the ball's rim and the reference's Fresnel noise
    local e = c.image.compare(gpu, ref).rel_rmse
    t.expect(e < 0.15, string.format("rel_rmse %.4f", e))
  end)
end

t.case("emission: read back; negative or non-numbers refused", function()
  local m = c.material.emissive { color = { 1, 1, 1 }, strength = 3 }
  t.expect(m.emission[1] == 3 and m.color[1] == 0, "emission 3, albedo 0")
  t.expect(c.material.diffuse { emission = { 0.5, 0, 0 } }.emission[1] == 0.5, "diffuse with emission")
  t.expect_error(function() c.material.emissive { strength = -1 } end, "strength")
  t.expect_error(function() c.material.diffuse { emission = { -1, 0, 0 } } end, "emission")
  t.expect_error(function() c.material.glass { emission = { 1, 1, 1 } } end, "emission")
end)
