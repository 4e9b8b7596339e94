-- Khronos glTF samples of materials (issue 50) as their READMEs describe
-- them, in both renderers: tests/scenes/khronos.lua frames each (192 px).
-- Each case holds the GPU to the reference (pixel centres, the graph's own
-- transport: no caustics) and checks what the sample's README says a
-- correct renderer shows. Bounds are issue 50's 0.15 rel_rmse; measured
-- (the reference reading a minified texture through the mip level its
-- pixel's footprint picks, as the GPU does: reference/ref_footprint.c):
-- TextureTransformTest 0.015, TextureSettingsTest 0.032, NormalTangentTest
-- 0.041, NormalTangentMirrorTest 0.052, DamagedHelmet 0.052,
-- AlphaBlendModeTest 0.066, SpecularTest 0.016, ClearCoatTest 0.037, ToyCar
-- 0.095, GlassVaseFlowers 0.111, GlassHurricaneCandleHolder 0.147. Point-sampling
-- level 0, the helmet was 0.173, AlphaBlendModeTest 0.162, ClearCoatTest
-- 0.143, TextureSettingsTest 0.133 and ToyCar 0.149.
local t = require "caustica.test"
local c = require "caustica"
local SCENE = "tests/scenes/khronos.lua"

local function both(sample)
  local set = { sample = sample }
  local gpu = t.render(SCENE, { set = set })
  t.expect_finite(gpu)
  local ref = t.reference(SCENE, { set = set, photons = 0, spp = 4, caustics = false })
  return gpu, ref
end

local function luminance_mean(img, x0, y0, x1, y1)
  local sum, n = 0, 0
  for y = y0, y1 do
    for x = x0, x1 do
      local r, g, b = img:pixel(x, y)
      sum, n = sum + 0.2126 * r + 0.7152 * g + 0.0722 * b, n + 1
    end
  end
  return sum / n
end

-- Every bump lit from the sun's side, the upper left: the upper left
-- quarter of the bump (about each tile's centre) brighter than the lower
-- right one. A bitangent of the wrong sign turns a bump into a dent, lit
-- from the lower right.
local function bumps_lit_from_upper_left(img, who, xs, ys)
  for _, cy in ipairs(ys) do
    for _, cx in ipairs(xs) do
      local ul = luminance_mean(img, cx - 6, cy - 6, cx - 1, cy - 1)
      local lr = luminance_mean(img, cx + 1, cy + 1, cx + 6, cy + 6)
      t.expect(ul > lr * 1.05, string.format("%s: the bump at (%d, %d): upper left %.3f, lower right %.3f", who,
                                             cx, cy, ul, lr))
    end
  end
end

-- How many pixels of the box [x0, x1] x [y0, y1] satisfy keep(r, g, b).
local function count(img, x0, y0, x1, y1, keep)
  local n = 0
  for y = y0, y1 do
    for x = x0, x1 do
      if keep(img:pixel(x, y)) then n = n + 1 end
    end
  end
  return n
end

-- rel_rmse of a against b over the box [x0, x1] x [y0, y1], of the means
-- of blocks of block x block pixels (1: of the pixels)
local function rel_box(a, b, x0, y0, x1, y1, block)
  local function mean(img, x, y)
    local s = { 0, 0, 0 }
    for j = 0, block - 1 do
      for i = 0, block - 1 do
        local p = { img:pixel(x + i, y + j) }
        for k = 1, 3 do s[k] = s[k] + p[k] / (block * block) end
      end
    end
    return s
  end
  local d2, n2 = 0, 0
  for y = y0, y1 - block + 1, block do
    for x = x0, x1 - block + 1, block do
      local p, q = mean(a, x, y), mean(b, x, y)
      for k = 1, 3 do
        d2, n2 = d2 + (p[k] - q[k]) ^ 2, n2 + q[k] ^ 2
      end
    end
  end
  return math.sqrt(d2 / n2)
end

local function within(gpu, ref, bound, what)
  local e = c.image.compare(gpu, ref).rel_rmse
  t.expect(e < bound, string.format("%s: rel_rmse %.4f (bound %g)", what, e, bound))
end

t.case("TextureTransformTest: KHR_texture_transform's offsets, rotation and scale, GPU within 0.15", function()
  -- its top row reads the UV texture offset by (0.5, 0), (0, 0.5) and
  -- (0.5, 0.5): green, blue and cyan checks on a coloured square where the
  -- offset applies, yellow where it does not
  local gpu, ref = both("texture_transform")
  within(gpu, ref, 0.15, "texture_transform")
  for _, img in ipairs { gpu, ref } do
    local yellow = count(img, 10, 40, 182, 90, function(r, g, b) return r > 0.4 and g > 0.4 and b < 0.1 end)
    t.expect(yellow < 20, string.format("%d yellow pixels in the offset row", yellow))
  end
end)

t.case("TextureSettingsTest: wrap modes, filters and a single-sided face, GPU within 0.15", function()
  -- Its "single-sided" row hides a red cross on the back of a face that
  -- is not doubleSided: culled by the camera, a green check shows behind
  -- it. Before doubleSided was read, both renderers showed the cross.
  local gpu, ref = both("texture_settings")
  within(gpu, ref, 0.15, "texture_settings")
  for name, img in pairs { shade = gpu, reference = ref } do
    local green = count(img, 96, 39, 110, 53, function(r, g, b) return g > 1.5 * r and g > 1.5 * b end)
    local red = count(img, 96, 39, 110, 53, function(r, g, b) return r > 1.5 * g and r > 1.5 * b end)
    t.expect(green > 10 and red < 3, string.format("%s: the single-sided cell holds %d green and %d red pixels",
                                                   name, green, red))
  end
end)

-- A normal-map sample: the GPU within 0.15, and every bump (tiles centred
-- at xs x ys) lit from the sun's side in both renderers.
local function bumps_case(sample, xs, ys)
  return function()
    local gpu, ref = both(sample)
    within(gpu, ref, 0.15, sample)
    for name, img in pairs { shade = gpu, reference = ref } do
      bumps_lit_from_upper_left(img, name, xs, ys)
    end
  end
end

-- (the pink and blue pairs: real geometry left, a normal-mapped quad right)
t.case("NormalTangentTest: tangents made at run time, the mapped half as the real one",
       bumps_case("normal_tangent", { 25, 48, 84, 108 }, { 27, 57, 87, 116, 146 }))

-- Before the bitangent took the mapping's handedness, the mirrored tiles'
-- bumps read as dents in both renderers.
t.case("NormalTangentMirrorTest: mirrored texture coordinates, every bump lit from the same side",
       bumps_case("normal_tangent_mirror", { 22, 41, 60, 79 }, { 45, 67, 91, 114, 136 }))

t.case("ToyCar: painted (not chrome), its windows seen through, its paint reflecting the cloth", function()
  -- Before, its metallicRoughnessTexture was reduced to its mean (> 0.5):
  -- the whole car a green chrome mirror; its windows, thin-walled glass,
  -- were refracted as the faces of a solid. Its clearcoated paint reflects
  -- the cloth under it in the reference, which traces the glossy lobes;
  -- `shade` reflects the environment alone, glossy_reflection puts the
  -- cloth it finds on screen there (docs/GLTF.md): 0.095 per pixel with it
  -- (bound 0.15), 0.133 without; 4 x 4 block means (bound 0.08).
  local gpu, ref = both("toy_car")
  within(gpu, ref, 0.15, "toy_car")
  local e = rel_box(gpu, ref, 0, 0, 191, 191, 4)
  t.expect(e < 0.08, string.format("4 x 4 block means: rel_rmse %.4f (bound 0.08)", e))
  local plain = t.render(SCENE, { set = { sample = "toy_car", glossy = false } })
  local with, without = c.image.compare(gpu, ref).rel_rmse, c.image.compare(plain, ref).rel_rmse
  t.expect(with < 0.92 * without, string.format("glossy_reflection: %.4f of the reference, %.4f without it", with,
                                                without))
  for name, img in pairs { shade = gpu, reference = ref } do
    -- the door: green paint lit by the sun
    local r, g, b = img:pixel(118, 128)
    t.expect(g > 1.5 * r and g > 1.5 * b and g > 0.05, string.format("%s: the door %.3f %.3f %.3f", name, r, g, b))
  end
end)

t.case("DamagedHelmet: every texture of a real asset, GPU within 0.15, its 4 x 4 block means within 0.08", function()
  -- The helmet's 2048^2 textures are minified about ten times at 192 px:
  -- both renderers filter them through the mip level the pixel's
  -- footprint picks: 0.052 (point-sampling level 0, the reference
  -- sharpened the emissive visor's thin lines: 0.173).
  local gpu, ref = both("damaged_helmet")
  within(gpu, ref, 0.15, "damaged_helmet")
  local e = rel_box(gpu, ref, 0, 0, 191, 191, 4)
  t.expect(e < 0.08, string.format("4 x 4 block means: rel_rmse %.4f (bound 0.08)", e))
end)

t.case("GlassHurricaneCandleHolder: the base colour texture colours the glass (its glTF logo), GPU within 0.15", function()
  -- Before, glass took its base colour factor alone: a plain blue holder,
  -- no logo, in both renderers. The reference with its photons (they
  -- light the candle inside through the glass), 16 iterations of its seed
  -- (not a time budget: the same image on a busy machine): 0.147 (bound
  -- 0.15; 0.153 while the reference read level 0 of the minified textures
  -- and cut its eye paths at 32 bounces). 86% of the squared error is in
  -- the glass, darker and bluer in the reference; the rest in its glossy
  -- foot, which reflects the blue bowl above it in the reference (the
  -- glossy lobes traced), the environment alone on the GPU.
  local set = { sample = "candle_holder" }
  local gpu = t.render(SCENE, { set = set })
  t.expect_finite(gpu)
  local ref = t.reference(SCENE, { set = set, spp = 16 })
  within(gpu, ref, 0.15, "candle_holder")
  for name, img in pairs { shade = gpu, reference = ref } do
    local green = count(img, 60, 60, 135, 105, function(r, g, b) return g > 1.3 * b and g > r end)
    t.expect(green > 500, string.format("%s: %d pixels of the green logo seen through the glass", name, green))
  end
end)

t.case("GlassVaseFlowers: the alpha-blended vase alike in both renderers, no frozen speckle, GPU within 0.15", function()
  -- Its left vase is alphaMode BLEND. The reference's coin per ray was a
  -- hash of the ray alone, and a pixel-centre ray is the same every
  -- iteration: the coins never changed, a speckle that did not average out
  -- (the left half 0.195 from the GPU at 16 iterations). Each iteration
  -- now salts the coins. The GPU's shadow of it is smooth (the shadow
  -- map's filter) where it was an ordered dither. The right vase is a
  -- solid shell of glass whose wall guides light by total internal
  -- reflection for hundreds of bounces: the reference cut its eye paths at
  -- 32 and drew a black band across the vase (0.169 over the whole image);
  -- followed to 1,024 bounces, 0.111 (bound 0.15).
  local set = { sample = "vase" }
  local gpu = t.render(SCENE, { set = set })
  t.expect_finite(gpu)
  local ref = t.reference(SCENE, { set = set, spp = 16 })
  local e = rel_box(gpu, ref, 0, 0, 95, 191, 1)
  t.expect(e < 0.12, string.format("the blended vase's half: rel_rmse %.4f (bound 0.12, measured 0.072)", e))
  within(gpu, ref, 0.15, "vase")
end)

t.case("SpecularTest: KHR_materials_specular's textures as its factors, in both renderers", function()
  -- Its rows 2, 4 and 6 read by specularTexture (A) and
  -- specularColorTexture (RGB) what rows 1, 3 and 5 say by factors; each
  -- sphere of a texture row as the one above it (the mean of 5 x 5 pixels
  -- at its centre, within 10% or 0.004). Before, the textures were listed
  -- as ignored: every texture row looked like factor 1 (the leftmost
  -- spheres, black by their factor of 0, were 0.012 in their texture row).
  local gpu, ref = both("specular")
  within(gpu, ref, 0.15, "specular")
  local xs, ys = { 106, 122, 139, 155, 171 }, { 47, 63, 79, 95, 111, 127 }
  local function centre(img, x, y)
    local s = { 0, 0, 0 }
    for j = -2, 2 do
      for i = -2, 2 do
        local p = { img:pixel(x + i, y + j) }
        for k = 1, 3 do s[k] = s[k] + p[k] / 25 end
      end
    end
    return s
  end
  for name, img in pairs { shade = gpu, reference = ref } do
    for row = 1, 5, 2 do
      for _, x in ipairs(xs) do
        local f, tx = centre(img, x, ys[row]), centre(img, x, ys[row + 1])
        for k = 1, 3 do
          t.expect(math.abs(tx[k] - f[k]) <= 0.1 * f[k] + 0.004,
                   string.format("%s: row %d, x %d, channel %d: by texture %.4f, by factor %.4f", name, row + 1, x, k,
                                 tx[k], f[k]))
        end
      end
    end
  end
end)

t.case("AlphaBlendModeTest: OPAQUE ignores alpha, BLEND blends, MASK cuts at its cutoffs", function()
  -- Its labels hide a red cross behind a green check wherever a mode is
  -- drawn right (OPAQUE drawing alpha, or BLEND not blending, shows the
  -- cross): seen at 384 px, the label row holds the two checks' green and
  -- no red in both renderers. Against the reference at 192 px, as the
  -- helmet, its minified textures through the same mip levels: 0.066
  -- (0.162 with level 0 in the reference); the blended box's shadow is
  -- smooth in both (the shadow map's filter; the reference's coins change
  -- every iteration).
  local gpu, ref = both("alpha_blend")
  within(gpu, ref, 0.15, "alpha_blend")
  local e = rel_box(gpu, ref, 0, 0, 191, 191, 4)
  t.expect(e < 0.08, string.format("4 x 4 block means: rel_rmse %.4f (bound 0.08)", e))
  local set = { sample = "alpha_blend", size = 384 }
  for name, img in pairs { shade = t.render(SCENE, { set = set }),
                           reference = (t.reference(SCENE, { set = set, photons = 0, spp = 4, caustics = false })) } do
    local green = count(img, 50, 228, 330, 246, function(r, g, b) return g > 1.3 * r and g > 1.3 * b and g > 0.1 end)
    local red = count(img, 50, 228, 330, 246, function(r, g, b) return r > 1.5 * g and r > 1.5 * b and r > 0.1 end)
    t.expect(green >= 10 and red == 0, string.format("%s: the labels show %d green and %d red pixels", name, green,
                                                     red))
  end
end)

t.case("ClearCoatTest: the coated column shows the base's and the coat's reflections, in both renderers", function()
  -- Its README: the middle column (KHR_materials_clearcoat) combines the
  -- left one (the base alone) and the right one (the coat alone as a black
  -- dielectric): (1 - clearcoat Fc) base + clearcoat Fc coat. Per row, the
  -- mean of the coated cell less the base's is at least 0.35 of the
  -- coat-only cell's mean (measured: 0.51 to 0.93 of it; the least where
  -- the reference's glossy rays off normal maps meet the surface itself,
  -- which the GPU's environment lookup does not know); with the extension ignored
  -- the two cells were alike (coated - base: 0.001 in the reference). Row 2 (partial coat)
  -- is left out: its coat-only cell blends with the backdrop. Against the
  -- reference (16 iterations): per pixel within 0.15 (0.037; 0.143 while
  -- the reference point-sampled the minified normal maps and labels at
  -- level 0), its 4 x 4 block means within 0.08.
  local set = { sample = "clearcoat" }
  local gpu = t.render(SCENE, { set = set })
  t.expect_finite(gpu)
  local ref = t.reference(SCENE, { set = set, photons = 0, spp = 16, caustics = false })
  within(gpu, ref, 0.15, "clearcoat")
  local e = rel_box(gpu, ref, 0, 0, 191, 191, 4)
  t.expect(e < 0.08, string.format("4 x 4 block means: rel_rmse %.4f (bound 0.08)", e))
  local cols = { { 61, 82 }, { 90, 111 }, { 118, 139 } }
  local rows = { { 21, 41 }, { 77, 97 }, { 105, 125 }, { 133, 154 }, { 161, 182 } }
  local names = { "simple coating", "roughness variations", "base normal map", "shared normal map",
                  "coat normal map" }
  for name, img in pairs { shade = gpu, reference = ref } do
    for i, r in ipairs(rows) do
      local m = {}
      for k, col in ipairs(cols) do m[k] = luminance_mean(img, col[1], r[1], col[2], r[2]) end
      local added = m[2] - m[1]
      t.expect(added >= 0.35 * m[3] and m[3] > 0.005,
               string.format("%s, %s: coated %.4f - base %.4f = %.4f; coat alone %.4f", name, names[i], m[2], m[1],
                             added, m[3]))
    end
  end
end)
