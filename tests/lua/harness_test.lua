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
