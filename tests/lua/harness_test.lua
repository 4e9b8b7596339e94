-- The harness's own comparisons: the statistical test for noisy images
-- (a third reference render passes against two others, a wrong image
-- fails), on the fog box's reference (tests/scenes/fog.lua): measured 97.6% of
-- the pixels within 4 standard deviations for a third seed, 80% for a fog
-- 30% denser.
local t = require "caustica.test"

local function ref(seed, set)
  return t.reference("tests/scenes/fog.lua", { set = set or {}, size = {24, 24}, photons = 0, spp = 4, seed = seed })
end

t.case("a Z-test per pixel: another seed passes, another scene fails", function()
  local refs = { ref(1), ref(2) }
  local got = t.expect_statistically_close(ref(3), refs, { z = 4, fraction = 0.95 })
  t.expect(got >= 0.95, string.format("%.3f of pixels within 4 sigma", got))
  -- a denser fog is another answer, not noise
  t.expect_error(function()
    t.expect_statistically_close(ref(3, { thickness = 1.3 }), refs, { z = 4, fraction = 0.95 })
  end, "standard deviations of the reference")
end)

-- The test API checks its arguments where a test calls it: a wrong one is an
-- error at the test's own line naming the function, the argument and what it
-- takes (before, t.expect_different(a, b) without its rmse failed inside
-- caustica's test.lua with "attempt to compare nil with number").
t.case("the test API's signatures are checked at the caller's line", function()
  local img = require("caustica.image").new(2, 2)
  local cases = {
    { function() t.expect_different(img, img) end,
      "harness_test.lua:29: bad argument #3 'rmse' to 't.expect_different' (a number expected, got nothing)" },
    { function() t.expect_close(img, "b.png") end,
      "bad argument #2 'b' to 't.expect_close' (an image (t.render, t.reference, c.image.load) expected, got a string)" },
    { function() t.expect_statistically_close(img, { img }) end,
      "bad argument #2 'refs' to 't.expect_statistically_close' (a table of two images ({ref1, ref2}) expected" },
    { function() t.expect_golden(img) end, "bad argument #2 'name' to 't.expect_golden' (a string expected, got nothing)" },
    { function() t.expect_finite({}) end, "bad argument #1 'img' to 't.expect_finite' (an image" },
    { function() t.render(42) end, "bad argument #1 'script' to 't.render' (a string expected, got a number)" },
    { function() t.reference("x.lua", "fast") end, "bad argument #2 'opts' to 't.reference' (a table or nil expected" },
    { function() t.expect_error("not a function") end, "bad argument #1 'fn' to 't.expect_error'" },
    { function() t.expect(true, 42) end, "bad argument #2 'message' to 't.expect' (a string or nil expected, got a number)" },
    { function() t.case("no function") end, "bad argument #2 'fn' to 't.case' (a function expected, got nothing)" },
    { function() t.fresnel("0.5", 1.5) end, "bad argument #1 'cos_i' to 't.fresnel' (a number expected, got a string)" },
  }
  for _, c in ipairs(cases) do
    local ok, err = pcall(c[1])
    t.expect(not ok and tostring(err):find(c[2], 1, true) ~= nil,
             "expected '" .. c[2] .. "', got '" .. tostring(err) .. "'")
  end
  -- right arguments still work
  t.expect_different(img, require("caustica.image").new(2, 2), 0)
end)
