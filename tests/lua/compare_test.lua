-- Issue 17's comparison scenes (scenes/compare/): every technique each
-- offers renders, finite, and the caustics techniques add light where plain
-- shading has none.
local t = require "caustica.test"
local c = require "caustica"

local scenes = {
  { "scenes/compare/ball.lua", "technique", { "plain", "photons", "illumination", "layered", "beams" } },
  { "scenes/compare/fog.lua", "technique", { "plain", "beams" } },
  { "scenes/compare/room.lua", "technique", { "plain", "huqin", "wyman", "layered", "sliced" } },
  { "scenes/compare/room.lua", "caustics", { "none", "photons", "illumination", "layered", "beams" } },
  { "scenes/compare/pool.lua", "technique", { "plain", "volumes", "photons", "beams" } },
  { "scenes/compare/dragon.lua", "technique", { "huqin", "wyman", "layered" } },
  { "scenes/compare/dragon.lua", "caustics", { "none", "photons", "layered", "beams" } },
}

t.case("every technique of every comparison scene renders", function()
  for _, s in ipairs(scenes) do
    local plain
    for i, name in ipairs(s[3]) do
      local img = t.render(s[1], { set = { [s[2]] = name }, size = {32, 32}, frame = (s[1]:find("fog") or s[1]:find("room")) and 0 or 3 })
      t.expect_finite(img)
      if i == 1 then
        plain = img
      elseif s[2] == "caustics" or (s[1]:find("ball") or s[1]:find("fog") or s[1]:find("pool")) then
        -- a caustics technique adds light (plain has none)
        t.expect(img:stats().mean_gray > plain:stats().mean_gray,
                 string.format("%s %s=%s adds light (%.4g against %.4g)", s[1], s[2], name, img:stats().mean_gray,
                               plain:stats().mean_gray))
      end
    end
  end
end)

t.case("photons light a pool floor seen from above through the water, as caustic volumes do", function()
  -- The caustic mapping once drew the water's depth too, hiding the floor
  -- under it: photons added nothing to the pool (0.1273 against plain's 0.1273).
  local mean = {}
  for _, name in ipairs { "plain", "photons", "volumes" } do
    mean[name] = t.render("scenes/compare/pool.lua", { set = { technique = name }, size = {64, 64}, frame = 30 })
                   :stats().mean_gray
  end
  t.expect(mean.photons - mean.plain > 0.6 * (mean.volumes - mean.plain),
           string.format("photons add %.4f over plain, volumes %.4f", mean.photons - mean.plain, mean.volumes - mean.plain))
end)
