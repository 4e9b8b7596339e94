-- Numerical care: degenerate input renders without NaN or Inf.
local t = require "caustica.test"

t.case("glass of IOR 1.0 is invisible in the single-interface shade", function()
  -- Fresnel reflectance is 0 when both sides match, and the refracted ray
  -- is the view ray: the sphere shows exactly the environment behind it.
  local with = t.render("tests/scenes/glass.lua", { set = { ior = 1.0 } })
  local without = t.render("tests/scenes/glass.lua", { set = { ior = 1.0, hide = true } })
  t.expect_close(with, without, { rmse = 2e-3 })
end)

for _, ior in ipairs { 0.8, 1.0, 1.33, 2.42 } do
  t.case("glass of IOR " .. ior .. " gives finite values (total internal reflection included)", function()
    local img = t.render("tests/scenes/glass.lua", { set = { ior = ior } })
    t.expect_finite(img)
  end)
end

t.case("zero-area triangles and a grazing camera stay finite", function()
  t.expect_finite(t.render("tests/scenes/degenerate.lua"))
end)

t.case("extreme morph weights and a deformer that returns NaN stay finite", function()
  t.expect_finite(t.render("tests/scenes/degenerate.lua", { set = { extreme = true } }))
end)
