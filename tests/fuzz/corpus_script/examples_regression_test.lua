-- A regression test of your own:
--   caustica test examples/regression_test.lua
-- (name your file *_test.lua under tests/lua to have `make test` run it).
local t = require "caustica.test"

t.case("the vignette darkens the corners", function()
  local img = t.render("examples/custom_pass.lua", { size = { 64, 64 } })
  t.expect_finite(img)
  local corner = img:stats(0, 0, 6, 6).mean_gray
  local centre = img:stats(29, 29, 35, 35).mean_gray
  t.expect(corner < centre, string.format("corner %.3f should be darker than centre %.3f", corner, centre))
end)

t.case("the vignette strength is a parameter", function()
  local weak = t.render("examples/custom_pass.lua", { size = { 64, 64 }, set = { strength = 0.1 } })
  local strong = t.render("examples/custom_pass.lua", { size = { 64, 64 }, set = { strength = 0.9 } })
  t.expect_different(weak, strong, 0.005)
end)
