-- Issue 17's comparison: a glass bunny in a room with a floor, walls and a
-- few objects (refraction). --set technique=plain|huqin|wyman|layered|sliced
-- (the refraction of the glass; plain: shade's one interface), and
-- caustics=none|photons|illumination|layered|beams.
local c = require "caustica"
local technique = c.param("technique", "layered")
local caustics = c.param("caustics", "none")
local scene = c.scene {
  camera = c.camera { eye = {0.3, 0.9, 2.6}, target = {0, 0.35, 0}, fov = 42 },
  environment = c.cubemap(c.asset "env/room"),
  ambient = {0.04, 0.04, 0.045},
}
local lamp = scene:add(c.light.spot { position = {0.8, 2.6, 1.2}, direction = {-0.8, -2.6, -1.2}, angle = 35,
                                      intensity = {9, 8.6, 8} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, material = c.material.diffuse { color = {0.7, 0.68, 0.62} } })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, 1.5, -1.4}, rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2),
                     material = c.material.diffuse { color = {0.45, 0.55, 0.7} } })
for i, box in ipairs { {-0.9, 0.7, 0.6, 0.3}, {0.8, 0.45, 0.4, 0.6}, {-0.4, -0.8, 0.3, 0.2} } do
  scene:add(c.object { mesh = c.mesh.box { size = {box[3], box[4], box[3]} }, position = {box[1], box[4] / 2, box[2] - 0.6},
                       material = c.material.diffuse { color = ({ {0.8, 0.3, 0.2}, {0.3, 0.7, 0.3}, {0.8, 0.7, 0.2} })[i] } })
end
scene:add(c.object { mesh = c.mesh.load(c.asset "bunny_15k.glb"), position = {0, 0.36, 0}, scale = {0.7, 0.7, 0.7},
                     material = c.material.glass { ior = 1.5 } })
local caustic_passes = {
  photons = function() return c.pass.photon_caustics { light = lamp } end,
  illumination = function() return c.pass.illumination_textures { light = lamp } end,
  layered = function() return c.pass.layered_caustics { light = lamp } end,
  beams = function() return c.pass.beam_caustics { light = lamp } end,
}
-- A view technique registered since (issue 54) joins at its defaults, under
-- its own name: --set technique=NAME, and bench --sweep technique=all.
local newer = c.techniques("view", { "refraction", "layered_refraction", "sliced_refraction" })
local newer_view, newer_list = {}, ""
for _, name in ipairs(newer) do newer_view[name], newer_list = true, newer_list .. ", " .. name end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = lamp, size = 1024 })
if caustics ~= "none" then
  assert(caustic_passes[caustics], "caustics: none, photons, illumination, layered or beams expected")
  g:add("caustics", caustic_passes[caustics]())
end
local irradiance = caustics ~= "none" and "caustics.irradiance" or nil
if technique == "plain" then
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = irradiance })
  g:output("shade.color")
else
  g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = irradiance, specular = false })
  if technique == "huqin" or technique == "wyman" then
    g:add("glass", c.pass.refraction { method = technique, color = "shade.color", shadow = "shadow.depth" })
  elseif technique == "layered" then
    g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  elseif technique == "sliced" then
    g:add("glass", c.pass.sliced_refraction { color = "shade.color" })
  elseif newer_view[technique] then
    g:add("glass", c.pass[technique] { color = "shade.color" })
  else
    error("technique: plain, huqin, wyman, layered, sliced" .. newer_list .. " expected, got " .. tostring(technique))
  end
  g:output("glass.color")
end
-- bench --sweep technique=all / choose: the refraction techniques without caustics, then the
-- caustics techniques under layered refraction; ranked by the whole image's error
local techniques = {
  metric = "image",
  { "plain", set = { technique = "plain", caustics = "none" } },
  { "huqin", set = { technique = "huqin", caustics = "none" },
    -- the paper's impostor rectangles and two interfaces, against the defaults
    points = { { ["glass.lookup"] = "impostors", ["glass.internal"] = 1 }, { ["glass.internal"] = 1 } } },
  { "wyman", set = { technique = "wyman", caustics = "none" } },
  { "layered", set = { technique = "layered", caustics = "none" }, sweep = { ["glass.layers"] = {4, 8} } },
  { "sliced", set = { technique = "sliced", caustics = "none" }, sweep = { ["glass.slices"] = {1, 3} } },
  { "layered+photons", set = { technique = "layered", caustics = "photons" },
    points = { { ["caustics.buffer"] = 512, ["caustics.texture"] = 512 } } },
  { "layered+illumination", set = { technique = "layered", caustics = "illumination" },
    points = { { ["caustics.planes"] = 8 } } },
  { "layered+layered", set = { technique = "layered", caustics = "layered" },
    sweep = { ["caustics.buffer"] = {128, 512} } },
  { "layered+beams", set = { technique = "layered", caustics = "beams" },
    points = { { ["caustics.refine"] = 0 }, { ["caustics.refine"] = 2 } } },
}
for _, name in ipairs(newer) do -- (at their defaults)
  techniques[#techniques + 1] = { name, set = { technique = name, caustics = "none" } }
end
return { scene = scene, graph = g, size = {256, 256}, techniques = techniques }
