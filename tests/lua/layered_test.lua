-- Chaudhari's refraction and caustics through every interface
-- (layered_refraction, layered_caustics) against the reference, closed
-- forms and the two-interface pass; and the cases that break image-space
-- tracers (tests/scenes/layered.lua, tir_cube.lua, ball_lens.lua).
local t = require "caustica.test"
local c = require "caustica"

local function render(script, set, size) return t.render(script, { set = set, size = size }) end

-- rel_rmse of a against b inside the refractor's silhouette (the pixels
-- where layered_refraction found a layer).
local function inside(a, b, script, set)
  local s = {}
  for k, v in pairs(set or {}) do s[k] = v end
  s.method, s.output = "layered", "glass.info"
  return c.image.compare(a, b, render(script, s)).rel_rmse
end

t.case("IOR 1.0 vanishes in a room: the image inside the silhouette is the object-free one", function()
  -- a floor, a back wall and four boxes behind the glass (issue 8's room):
  -- leaving rays find them in screen space, so the identity holds to the
  -- float precision of the march; measured 4.6e-8, 1.2e-8 and 7e-3 (the
  -- dragon: rays leaving at its thin silhouettes onto the boxes' edges)
  for object, tol in pairs { sphere = 1e-4, bunny = 1e-4, dragon = 0.03 } do
    -- no shadow pass (the shadow map would make the glass opaque to the lamp)
    local set = { object = object, room = true, ior = 1.0, shadows = false }
    local img = render("tests/scenes/layered.lua", set)
    local free = render("tests/scenes/layered.lua", { object = object, room = true, hide = true, shadows = false })
    t.expect_finite(img)
    local e = inside(img, free, "tests/scenes/layered.lua", set)
    t.expect(e < tol, string.format("%s: rel_rmse inside the silhouette %.3g", object, e))
  end
end)

t.case("more than two interfaces: a torus against the reference, better than the two-interface pass", function()
  local set = { object = "torus" }
  local ref = t.reference("tests/scenes/layered.lua", { set = set, photons = 0, spp = 32 })
  local layered = render("tests/scenes/layered.lua", set)
  -- the two-interface pass as the paper has it (internal = 1: no
  -- internal reflections followed, which since issue 8 it can)
  local huqin = render("tests/scenes/layered.lua", { object = "torus", method = "huqin", internal = 1 })
  local el = c.image.compare(layered, ref).rel_rmse
  local eh = c.image.compare(huqin, ref).rel_rmse
  -- measured 0.065 and 0.174 (against 64 reference samples); since issue 8's
  -- exit decision and secant iteration the two-interface pass gets 0.081
  t.expect(el < 0.09, string.format("layered rel_rmse %.4f", el))
  -- (0.075 with internal = 1 since issue 8's changes to its exits)
  t.expect(el < eh, string.format("layered %.4f, huqin %.4f", el, eh))
end)

t.case("a glass ball in an environment: within 7% of the reference, below the two-interface pass's error", function()
  local ref = t.reference("tests/scenes/layered.lua", { photons = 0, spp = 32 })
  local img = render("tests/scenes/layered.lua", {})
  local huqin = render("tests/scenes/layered.lua", { method = "huqin", internal = 1 })
  local e, eh = c.image.compare(img, ref).rel_rmse, c.image.compare(huqin, ref).rel_rmse
  -- measured 0.053 and 0.105 against 64 reference samples; 0.058 and 0.068
  -- since issue 8's exit decision and secant iteration (the rim's rings gone)
  t.expect(e < 0.07 and e < 0.92 * eh, string.format("rel_rmse %.4f, huqin %.4f", e, eh))
end)

t.case("total internal reflection: the IOR 2.42 cube and an IOR 0.8 cube against the reference", function()
  -- issue 8's cube: about a third of its rays leave after one or two total
  -- internal reflections; measured (over the cube) against 64 samples
  for ior, tol in pairs { [2.42] = 0.25, [0.8] = 0.15 } do
    local set = { ior = ior }
    local ref = t.reference("tests/scenes/tir_cube.lua", { set = set, photons = 0, spp = 32, size = {128, 128} })
    local s = { ior = ior, method = "layered" }
    local img = t.render("tests/scenes/tir_cube.lua", { set = s, size = {128, 128} })
    -- the paper's two interfaces (internal = 1)
    local huqin = t.render("tests/scenes/tir_cube.lua", { set = { ior = ior, internal = 1 }, size = {128, 128} })
    local mask = t.render("tests/scenes/tir_cube.lua", { set = { ior = ior, method = "layered", output = "info" }, size = {128, 128} })
    local el = c.image.compare(img, ref, mask).rel_rmse
    local eh = c.image.compare(huqin, ref, mask).rel_rmse
    -- at IOR 0.8 (total internal reflection at the entry, outside) the
    -- two-interface pass is ahead since issue 8's exit changes: 0.120
    -- against layered 0.149; at 2.42 layered's every interface still wins
    t.expect(el < tol and (ior < 1 or el < eh),
             string.format("IOR %g over the cube: layered %.4f, huqin %.4f", ior, el, eh))
    -- the paths do meet total internal reflection
    local info = mask:stats()
    if ior > 2 then t.expect(info.max > 2, "interfaces per path: max " .. info.max) end
  end
end)

t.case("caustics of a ball lens at its paraxial focus: encircled power within 2% of the closed form", function()
  -- R = 1, n = 1.5, an ideal interface, the floor 1.5 below the centre, a
  -- vertical directional light of irradiance 1: within r = 0.1 of the axis
  -- the floor gets 0.406 of the power through the ball (pi R^2), issue 8's
  -- closed form. The camera looks straight down from 0.2 above the floor,
  -- so every pixel covers the same floor area. Measured 0.4083 at buffers
  -- 256, 512 and 1024.
  local n, h = 128, 0.2
  local set = { technique = "layered", view = "down", floor = 1.5, radius = 1, camera_height = h, fresnel = false,
                output = "irradiance", buffer = 256 }
  local img = t.render("tests/scenes/ball_lens.lua", { set = set, size = {n, n} })
  t.expect_finite(img)
  local side = 2 * h * math.tan(math.rad(30)) / n
  local p = 0
  for y = 0, n - 1 do
    for x = 0, n - 1 do
      local px, py = (x + 0.5 - n / 2) * side, (y + 0.5 - n / 2) * side
      if px * px + py * py < 0.01 then p = p + img:pixel(x, y) * side * side end
    end
  end
  local fraction = p / math.pi
  t.expect(math.abs(fraction / 0.406 - 1) < 0.02, string.format("encircled fraction %.4f (closed form 0.406)", fraction))
end)

t.case("caustics carry no more than the light through the glass, and follow reflection off the outside", function()
  -- the whole floor from above the light's side: the caustic power is at
  -- most the power through the ball (pi R^2 x E)
  local set = { technique = "layered", view = "down", floor = 1.5, radius = 1, camera_height = 1.0, output = "irradiance" }
  local img = t.render("tests/scenes/ball_lens.lua", { set = set, size = {128, 128} })
  local side = 2 * 1.0 * math.tan(math.rad(30)) / 128
  local total = 0
  for y = 0, 127 do for x = 0, 127 do total = total + img:pixel(x, y) * side * side end end
  t.expect(total <= math.pi * 1.0001 and total > 0.5 * math.pi, string.format("caustic power %.4f of pi", total))
  -- IOR 0.8: light entering is totally reflected off the outside at grazing
  -- angles, a photon of its own; nothing is NaN
  t.expect_finite(t.render("tests/scenes/ball_lens.lua", { set = { technique = "layered", ior = 0.8, view = "down",
                                                                    floor = 1.5, radius = 1, output = "irradiance" } }))
end)

t.case("stability: grazing views, thin features, overflow, a ray that never leaves, inside-out meshes", function()
  local script = "tests/scenes/layered.lua"
  -- more surfaces than layers: the deeper ones are dropped and counted
  local info = render(script, { object = "bunnies", layers = 2, output = "glass.info" })
  local dropped = 0
  for y = 0, 127, 2 do for x = 0, 127, 2 do local _, g = info:pixel(x, y); dropped = math.max(dropped, g) end end
  t.expect(dropped > 0, "surfaces past `layers` are counted in info.g")
  t.expect_finite(render(script, { object = "bunnies", layers = 2 }))
  -- a cap of 3 interfaces stops the torus's long paths (info.a + 100)
  local capped = render("tests/scenes/layered.lua", { object = "torus", output = "glass.info", interfaces = 3 })
  local any_capped = false
  for y = 0, 127 do for x = 0, 127 do if select(4, capped:pixel(x, y)) >= 100 then any_capped = true end end end
  t.expect(any_capped, "the interface cap is reported")
  for _, set in ipairs {
    { object = "torus", interfaces = 3 },
    { object = "sphere", ior = 0.8 }, { object = "sphere", ior = 1.0 }, { object = "sphere", ior = 4.0 },
    { object = "dragon", voxels = 128, layers = 32 }, { object = "dragon", depths = "voxel", normals = "gradient" },
    { object = "bunny", search = 0, steps = 1 }, { object = "thin" }, { object = "inside_out" },
    { object = "sphere", view = "grazing" }, { object = "sphere", view = "inside" },
  } do
    local img = render(script, set)
    t.expect_finite(img)
  end
  -- no refractor in view: the input passes through unchanged
  local hidden = render(script, { hide = true })
  local plain = render(script, { hide = true, method = "huqin" })
  t.expect(c.image.compare(hidden, plain).max < 1e-6, "hidden refractor: the input unchanged")
end)

t.case("the deforming dragon (Fig. 4.2) takes its layers again every frame", function()
  local a = render("scenes/chaudhari_fig42.lua", { model = "40k" }, {96, 96})
  local b = t.render("scenes/chaudhari_fig42.lua", { set = { model = "40k" }, size = {96, 96}, frame = 20 })
  t.expect_finite(a)
  t.expect_finite(b)
  t.expect(c.image.compare(a, b).rmse > 1e-3, "the swaying dragon changes the image")
end)

t.case("Fresnel with total internal reflection: the light an exit reflects back inside is followed (issue 27)", function()
  -- The IOR 2.42 cube with Fresnel on: where the reference's path meets a
  -- total internal reflection, the exit after it is near the critical angle
  -- and reflects most of the light back inside. The thesis's one path drops
  -- that part (internal = 0): 198 of 2,051 such pixels were within 10% of
  -- the reference; following it (internal = 2) 1,438 (1,871 with an ideal
  -- interface, where nothing is dropped).
  local function within(set)
    local tir = t.reference("tests/scenes/tir_cube.lua", { set = { fresnel = true }, aov = "tir", size = {128, 128} })
    local ref = t.reference("tests/scenes/tir_cube.lua", { set = { fresnel = true }, photons = 0, spp = 32, size = {128, 128} })
    local img = t.render("tests/scenes/tir_cube.lua", { set = set, size = {128, 128} })
    local good, n = t.count_within(img, ref, tir, 0.1)
    return good / n, n
  end
  local followed, n = within { method = "layered", fresnel = true }
  local dropped = within { method = "layered", fresnel = true, internal = 0 }
  t.expect(n > 1500, "pixels with total internal reflection: " .. n)
  t.expect(followed > 0.65, string.format("followed: %.3f of them within 10%%", followed))
  t.expect(dropped < 0.2, string.format("dropped (the thesis): %.3f within 10%%", dropped))
end)
