-- The scene a glTF file is when no script is given (issue 51):
-- `caustica render|record|run|info|reference|bench model.glb` runs this
-- script for the file (src/app/session.c). What it chooses, in order:
--
-- - the file's objects where its node tree puts them (c.gltf.load);
-- - its camera: --set camera=NAME (or a number from 1), else its first,
--   else one framing the objects from the front and a little above;
-- - its lights (KHR_lights_punctual), else a sun from the upper left, and
--   always an ambient sky (`ambient`, default 0.2);
-- - a grey floor under the objects as a receiver, unless the file has one
--   (--set ground=false: none);
-- - the graph: a shadow map of the first light, photon caustics where
--   the file holds glass (--set caustics=layered|beams|illumination|none
--   for another technique; `techniques` lists them for bench and choose),
--   shade, and refraction through the glass (each pass at its defaults);
-- - its animations all playing (the first alone where two drive the same
--   node; --set animation=NAME or a number: that one), frames = the
--   longest at --fps N (the command line puts it in --set fps=N; 24), looped;
-- - the image 512 px high, as wide as the camera's aspectRatio asks (1:1
--   without one); --size overrides.
--
-- `caustica info model.glb` prints what was chosen; `caustica info
-- model.glb --script` writes this script for the file, to start from.
local c = require "caustica"
local host = require "caustica.host"

local path = host.script() -- info --script: the file
local scene_choice = c.param("scene", "")
-- the file by its name: relative paths resolve against its own folder, and
-- an error is the file's, not this script's line
local ok, file = pcall(c.gltf.load, path:match("[^/]+$"), -- info --script: by its path
                       scene_choice ~= "" and { scene = tonumber(scene_choice) or scene_choice } or nil)
if not ok then error(tostring(file):gsub("^[^\n]-gltf_scene%.lua:%d+: ", ""), 0) end
if #file.objects == 0 then
  error(string.format("%s: its scene '%s' holds no node with a mesh: nothing to render", path, file.name), 0)
end

local scene = c.scene { ambient = { c.param("ambient", 0.2), c.param("ambient", 0.2), c.param("ambient", 0.2) },
                        background = { 0.05, 0.05, 0.06 } }
local glass = false
for _, o in ipairs(file.objects) do
  scene:add(o)
  local ms = o.materials
  for i = 1, #ms do glass = glass or ms[i].kind == "glass" or ms[i].kind == "water" end
end

-- the camera
local want = c.param("camera", "")
local camera, aspect = nil, nil
if want ~= "" then
  camera = file.cameras[tonumber(want) or want]
  if not camera then
    local names = {}
    for k in pairs(file.cameras) do if type(k) == "string" then names[#names + 1] = k end end
    table.sort(names)
    error(string.format("%s: --set camera=%s: the file has no such camera (it has %d%s)", path, want,
                        #file.cameras, #names > 0 and ": " .. table.concat(names, ", ") or ""), 0)
  end
else
  camera = file.cameras[1]
end
if camera then
  -- the aspect ratio its glTF camera asks for
  for i, cam in ipairs(file.cameras) do
    if cam == camera then
      local info = file.camera_info[i]
      aspect = info.aspect or (info.xmag and math.abs(info.xmag / info.ymag))
    end
  end
else
  camera = file.framing_camera()
end
scene.camera = camera

-- the lights
local lights = {}
for _, l in ipairs(file.lights) do lights[#lights + 1] = scene:add(l) end
if #lights == 0 then
  lights[1] = scene:add(c.light.directional { direction = { -0.4, -1, -0.6 }, intensity = { 2, 2, 1.95 } })
end

-- the floor, unless the file has its own: an object flat in y at the
-- bottom of the others, under at least half of their width and depth
local bounds = file.bounds()
local function has_floor()
  local lo, hi = bounds[1], bounds[2]
  local extent = math.max(hi[1] - lo[1], hi[3] - lo[3], hi[2] - lo[2], 1e-6)
  for _, o in ipairs(file.objects) do
    local b = o.bounds
    if b[2][2] - b[1][2] <= 0.01 * extent and b[2][2] <= lo[2] + 0.01 * extent
       and b[2][1] - b[1][1] >= 0.5 * (hi[1] - lo[1]) and b[2][3] - b[1][3] >= 0.5 * (hi[3] - lo[3]) then
      return true
    end
  end
  return false
end
if c.param("ground", true) and not has_floor() then
  local lo, hi = bounds[1], bounds[2]
  local extent = math.max(hi[1] - lo[1], hi[3] - lo[3], hi[2] - lo[2], 1e-3)
  scene:add(c.object { mesh = c.mesh.plane { size = 6 * extent },
                       position = { (lo[1] + hi[1]) / 2, lo[2] - 1e-3 * extent, (lo[3] + hi[3]) / 2 },
                       material = c.material.diffuse { color = { 0.7, 0.7, 0.68 } } })
end

-- the graph
local light = lights[1]
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = light })
-- --set caustics=photons|layered|beams|illumination|none picks the
-- caustics technique (bench and choose sweep them: `techniques` below)
local CAUSTICS = { photons = "photon_caustics", layered = "layered_caustics", beams = "beam_caustics",
                   illumination = "illumination_textures" }
local technique = c.param("caustics", "photons")
if technique ~= "none" and not CAUSTICS[technique] then
  error(string.format("%s: --set caustics=%s: expected photons, layered, beams, illumination or none", path,
                      technique), 0)
end
local caustics
if glass and technique ~= "none" then
  g:add("caustics", c.pass[CAUSTICS[technique]] { light = light })
  caustics = "caustics.irradiance"
end
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = caustics })
if glass then
  g:add("glass", c.pass.refraction { color = "shade.color", depth = "shade.depth" })
  g:output("glass.color")
else
  g:output("shade.color")
end

-- the animations
local which = c.param("animation", "")
local playing = {}
if which ~= "" then
  playing[1] = file.animations[tonumber(which) or which]
  if not playing[1] then
    error(string.format("%s: --set animation=%s: the file has no such animation (it has %d)", path, which,
                        #file.animations), 0)
  end
else
  -- all of them, unless two drive the same node (a character's walk and
  -- run): then the first alone, as a viewer plays a file
  local driven, overlap = {}, false
  for i, a in ipairs(file.file.animations) do
    local mine = {}
    for _, n in ipairs(a.nodes) do
      if driven[n] and driven[n] ~= i then overlap = true end
      mine[n] = true
    end
    for n in pairs(mine) do driven[n] = i end
  end
  playing = overlap and { file.animations[1] } or file.animations
end
local fps = c.param("fps", 24)
local longest = 0
for _, a in ipairs(playing) do longest = math.max(longest, a.duration) end

local height = 512
return {
  scene = scene, graph = g,
  -- bench --sweep technique=all and choose: each caustics technique at its
  -- defaults, ranked by the whole image's error
  techniques = glass and {
    metric = "image",
    { "none", set = { caustics = "none" } },
    { "photons", set = { caustics = "photons" } },
    { "layered", set = { caustics = "layered" } },
    { "beams", set = { caustics = "beams" } },
    { "illumination", set = { caustics = "illumination" } },
  } or nil,
  size = { math.max(1, math.floor(height * (aspect or 1) + 0.5)), height },
  frames = math.max(1, math.floor(longest * fps + 0.5)), fps = fps,
  update = #playing > 0 and function(t)
    for _, a in ipairs(playing) do a:apply(t) end
    scene.camera = camera
  end or nil,
}
