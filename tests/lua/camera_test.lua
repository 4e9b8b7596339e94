-- The orthographic camera: c.camera { ortho = { width = W } }.
local t = require "caustica.test"
local c = require "caustica"

t.case("ortho: the GPU and the reference see the same parallel projection", function()
  -- a diffuse cube and its shadow seen straight down; measured rel_rmse
  -- 0.046 (0.021 for the perspective camera): the difference is the shadow
  -- map's edge, which covers more pixels in this view
  for _, ortho in ipairs { true, false } do
    local gpu = t.render("tests/scenes/ortho.lua", { set = { shape = "cube", ortho = ortho } })
    local ref = t.reference("tests/scenes/ortho.lua", { set = { shape = "cube", ortho = ortho }, photons = 0, spp = 4 })
    local e = c.image.compare(gpu, ref).rel_rmse
    t.expect(e < (ortho and 0.06 or 0.03), string.format("ortho = %s: rel_rmse %.4f", tostring(ortho), e))
  end
end)

t.case("ortho: moving the camera back along its axis changes nothing; its width scales the view", function()
  local near = t.render("tests/scenes/ortho.lua", { set = { shape = "cube" } })
  local far = t.render("tests/scenes/ortho.lua", { set = { shape = "cube", height = 6 } })
  t.expect(c.image.compare(near, far).rel_rmse < 1e-3, "the same image from twice as far")
  -- the cube's top, 0.6 wide from x = 0 to 0.6: 0.3 x 0.3 of a view 2 wide;
  -- in a view 1 wide it runs off the edge at x = 0.5, so 0.5 x 0.6
  local function cube_pixels(img)
    local n = 0
    for y = 0, 63 do
      for x = 0, 63 do
        local r, g = img:pixel(x, y)
        if r > 1.5 * g then n = n + 1 end
      end
    end
    return n
  end
  local narrow = t.render("tests/scenes/ortho.lua", { set = { shape = "cube", width = 1.0 } })
  local a, b = cube_pixels(near), cube_pixels(narrow)
  t.expect(math.abs(a - (0.3 * 64) ^ 2) < 30, string.format("width 2: %d pixels, expected %.0f", a, (0.3 * 64) ^ 2))
  t.expect(math.abs(b - 0.5 * 0.6 * 64 * 64) < 60, string.format("width 1: %d pixels, expected %.0f", b, 0.3 * 64 * 64))
end)

t.case("ortho: refraction and photon caustics stay finite; the value reads back; bad values are refused", function()
  t.expect_finite(t.render("tests/scenes/ortho.lua"))
  t.expect_finite(t.reference("tests/scenes/ortho.lua", { photons = 20000, spp = 2 }))
  local cam = c.camera { eye = {0, 3, 0}, target = {0, 0, 0}, up = {0, 0, -1}, ortho = { width = 4 } }
  t.expect(cam.ortho.width == 4, "ortho.width")
  cam.ortho = false
  t.expect(cam.ortho == false, "back to perspective")
  t.expect_error(function() c.camera { ortho = { width = -1 } } end, "positive width")
  t.expect_error(function() c.camera { ortho = { height = 2 } } end, "height")
  t.expect_error(function() c.camera { ortho = 3 } end, "table { width = W } or false")
end)

t.case("tiny near planes (1e-5, 1e-7) and a far one (1e6) still render the frame", function()
  -- issue 27 met a whole frame of 0 at near = 1e-5 under an orthographic
  -- camera. An orthographic camera's depth is linear: a tiny near changes
  -- nothing. Elsewhere the depth steps grow (perspective: distance^2 /
  -- near; orthographic: far / 2^24) and only the sphere's rim may differ
  -- (measured 0.011 and 0.054; graph_lint warns, tests/cli/info_test.sh).
  for _, ortho in ipairs { true, false } do
    local base = t.render("tests/scenes/ortho.lua", { set = { ortho = ortho } })
    t.expect(base:stats().mean_gray > 0.05, "the floor is lit")
    for _, nf in ipairs { { 1e-5, 100 }, { 1e-7, 100 }, { 1e-5, 1e6 } } do
      local img = t.render("tests/scenes/ortho.lua", { set = { ortho = ortho, near = nf[1], far = nf[2] } })
      t.expect_finite(img)
      local exact = ortho and nf[2] == 100
      t.expect_close(img, base, { rel_rmse = exact and 1e-4 or 0.08 })
    end
  end
end)
