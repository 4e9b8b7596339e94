-- The render graph and user-written passes.
local t = require "caustica.test"

t.case("fullscreen pass: samplers by name, uniforms by value", function()
  local shaded = t.render("tests/scenes/passes.lua", { set = { mode = "environment" } })
  local inverted = t.render("tests/scenes/passes.lua", { set = { mode = "fullscreen" } })
  for _, p in ipairs { { 5, 5 }, { 32, 32 }, { 60, 50 } } do
    local c = { shaded:pixel(p[1], p[2]) }
    local d = { inverted:pixel(p[1], p[2]) }
    for k = 1, 3 do
      t.expect(math.abs(d[k] - 0.5 * (1 - c[k])) < 1e-5,
        string.format("pixel %d,%d channel %d: %g vs 0.5 * (1 - %g)", p[1], p[2], k, d[k], c[k]))
    end
  end
end)

t.case("custom pass written in Lua clears its output", function()
  local img = t.render("tests/scenes/passes.lua", { set = { mode = "custom" } })
  local r, g, b = img:pixel(10, 10)
  t.expect(r == 0.25 and g == 0.5 and b == 0.75, string.format("%g %g %g", r, g, b))
end)

t.case("environment pass equals the background the shade pass draws", function()
  local env = t.render("tests/scenes/passes.lua", { set = { mode = "env_only" } })
  local shaded = t.render("tests/scenes/passes.lua", { set = { mode = "environment" } })
  -- top rows see only the environment in both
  local a, b = env:stats(0, 0, 64, 8), shaded:stats(0, 0, 64, 8)
  t.expect(math.abs(a.mean_gray - b.mean_gray) < 1e-6, a.mean_gray .. " vs " .. b.mean_gray)
  t.expect(a.mean_gray > 0.05, "the environment is not black")
end)

t.case("a pass that contributes nothing is left out and costs nothing", function()
  local img, ms = t.render("tests/scenes/passes.lua", { set = { mode = "prune" } })
  t.expect(ms.unused == nil, "the pruned pass has no timing")
  t.expect(ms.shade ~= nil and ms.shade >= 0, "the shade pass was timed")
end)

t.case("errors from scripts carry the script's file and line", function()
  t.expect_error(function() t.render("tests/scenes/passes.lua", { set = { mode = "broken_shader" } }) end,
    "broken.frag:7: error")
  t.expect_error(function() t.render("tests/scenes/passes.lua", { set = { mode = "late_input" } }) end,
    "move 'shade' before 'invert'")
end)

t.case("the documented refraction example needs no depth: it defaults to the colour pass's depth", function()
  local c = require "caustica"
  local p = c.pass.refraction { method = "huqin", color = "shade.color", iterations = 3 }
  t.expect(p.kind == "refraction", "a refraction pass")
  local with = t.render("tests/scenes/refract.lua")
  local without = t.render("tests/scenes/refract.lua", { set = { default_depth = true } })
  t.expect_close(with, without, { rmse = 0 })
end)
