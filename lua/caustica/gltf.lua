-- c.gltf.load: a glTF file as a scene (issue 51; docs/GLTF_SCENES.md).
-- Over the file `c.gltf.open` reads (src/lua/l_gltf.c), it makes an
-- object of every node with a mesh, a camera of every node with a camera
-- and a light of every node with a KHR_lights_punctual light, in the
-- chosen scene, placed where the node tree puts them, and the file's
-- animations as values that move them:
--
--   local file = c.gltf.load("car.glb", { scene = "Main" })
--   for _, o in ipairs(file.objects) do scene:add(o) end
--   file.objects.Glass.material = c.material.glass { ior = 1.5 }
--   scene.camera = file.cameras[1]
--   ... update = function(t) file.animations[1]:apply(t) end
--
-- objects, cameras, lights and animations are lists in the file's order,
-- also keyed by name (the first of a name wins).
local M = {}

-- Lights: glTF gives candela (point, spot) and lux (directional);
-- caustica's lights are radiometric (W/sr, W/m^2): divided by 683 lm/W,
-- the luminous efficacy of light at 555 nm, which is how the photometric
-- units are defined. Blender's exporter (3.4, "Khronos glTF Blender I/O")
-- writes a point or spot light's W as W / 4 pi x 683 candela, but a sun's
-- W/m^2 as that many lux without the 683: its suns are taken as W/m^2.
M.LUMENS_PER_WATT = 683

-- v rotated by the unit quaternion q = {x, y, z, w}.
local function rotate(q, v)
  local x, y, z, w = q[1], q[2], q[3], q[4]
  -- t = 2 q.xyz x v; v' = v + w t + q.xyz x t
  local tx, ty, tz = 2 * (y * v[3] - z * v[2]), 2 * (z * v[1] - x * v[3]), 2 * (x * v[2] - y * v[1])
  return { v[1] + w * tx + (y * tz - z * ty), v[2] + w * ty + (z * tx - x * tz), v[3] + w * tz + (x * ty - y * tx) }
end
M.rotate = rotate

local function camera_place(cam, pose)
  local eye = pose.position
  local forward, up = rotate(pose.rotation, { 0, 0, -1 }), rotate(pose.rotation, { 0, 1, 0 })
  cam.eye = eye
  cam.target = { eye[1] + forward[1], eye[2] + forward[2], eye[3] + forward[3] }
  cam.up = up
end

local function light_place(light, kind, pose)
  if kind ~= "directional" then light.position = pose.position end
  if kind ~= "point" then light.direction = rotate(pose.rotation, { 0, 0, -1 }) end
end

-- A skinned node's object stands where its joints put it: its own
-- transform is the identity (glTF 2.0 §3.7.3.3 has the skinned mesh's node
-- transform ignored) and `joints` its skin's matrices.
local function object_place(obj, pose, joints)
  if joints then
    obj.position, obj.rotation, obj.scale = { 0, 0, 0 }, { 0, 0, 0, 1 }, { 1, 1, 1 }
    obj.joint_matrices = joints
  else
    obj.position, obj.rotation, obj.scale = pose.position, pose.rotation, pose.scale
  end
  if #pose.weights > 0 then obj.morph_weights = pose.weights end
end

local function add(list, name, value)
  list[#list + 1] = value
  if list[name] == nil then list[name] = value end
end

local function make_camera(c, info, pose)
  local far = info.zfar or math.max(1000, info.znear * 1e5) -- glTF: no zfar, an infinite projection
  local cam
  if info.type == "orthographic" then
    cam = c.camera { ortho = { width = 2 * math.abs(info.xmag) }, near = math.max(info.znear, 1e-6), far = far }
  else
    cam = c.camera { fov = math.deg(info.yfov), near = info.znear, far = far }
  end
  camera_place(cam, pose)
  return cam
end

local function make_light(c, info, pose, generator)
  local k = info.intensity / M.LUMENS_PER_WATT
  if info.type == "directional" and generator:find("^Khronos glTF Blender I/O") then k = info.intensity end
  local intensity = { info.color[1] * k, info.color[2] * k, info.color[3] * k }
  local light
  if info.type == "directional" then
    light = c.light.directional { intensity = intensity, direction = { 0, -1, 0 } }
  elseif info.type == "point" then
    light = c.light.point { intensity = intensity, position = { 0, 0, 0 } }
  else
    local outer = math.max(info.outer_cone, 1e-3)
    light = c.light.spot { intensity = intensity, position = { 0, 0, 0 }, direction = { 0, -1, 0 },
                           angle = math.min(math.deg(outer), 90),
                           softness = math.min(math.max((outer - info.inner_cone) / outer, 0), 1) }
  end
  light_place(light, info.type, pose)
  return light
end

local Animation = {}
Animation.__index = Animation

--- anim:apply(t [, { loop = true }]): moves what the animation drives to
--- where it is t seconds in (looped over [start, stop] unless loop = false,
--- which holds the last key). A moved camera is the file's camera value:
--- `scene.camera = file.cameras[1]` again puts it in the scene.
function Animation:apply(t, opts)
  local loop = not (opts and opts.loop == false)
  local span = self.stop - self.start
  local at = self.start + t
  if loop and span > 0 then at = self.start + (t % span) end
  local poses, skins = self.file:pose(self.index, at)
  for node, obj in pairs(self.bindings.objects) do
    local skin = self.bindings.skins[node]
    object_place(obj, poses[node], skin and skins[skin])
  end
  for node, cam in pairs(self.bindings.cameras) do camera_place(cam, poses[node]) end
  for node, l in pairs(self.bindings.lights) do light_place(l.light, l.kind, poses[node]) end
  return self
end

-- The world box {min, max} of `objects` where they stand now (each
-- object's own box: its mesh through its transform, or its skin as posed),
-- nil when there are none.
local function objects_bounds(objects)
  local lo, hi
  for _, o in ipairs(objects) do
    local b = o.bounds
    lo = lo and { math.min(lo[1], b[1][1]), math.min(lo[2], b[1][2]), math.min(lo[3], b[1][3]) } or b[1]
    hi = hi and { math.max(hi[1], b[2][1]), math.max(hi[2], b[2][2]), math.max(hi[3], b[2][3]) } or b[2]
  end
  return lo and { lo, hi } or nil
end
M.objects_bounds = objects_bounds

--- A perspective camera of `fov` degrees (45) that frames the box from the
--- front and a little above (+z, +y: glTF's front and up), the whole of its
--- bounding sphere in view.
function M.framing_camera(c, bounds, fov)
  fov = fov or 45
  local lo, hi = bounds[1], bounds[2]
  local centre = { (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2, (lo[3] + hi[3]) / 2 }
  local r = 0.5 * math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
  r = math.max(r, 1e-4)
  local d = 1.1 * r / math.sin(math.rad(fov) / 2)
  local dir = { 0, 0.34, 0.94 }
  return c.camera { eye = { centre[1] + dir[1] * d, centre[2] + dir[2] * d, centre[3] + dir[3] * d },
                    target = centre, fov = fov, near = math.max(d - 1.5 * r, d * 1e-3), far = d + 4 * r }
end

local function load(c, path, opts)
  local file = c.gltf.open(path, opts)
  local poses, skins = file:pose(nil, 0)
  local out = { name = file.name, file = file, nodes = file.nodes, objects = {}, cameras = {}, lights = {},
                animations = {}, camera_info = {} }
  local bindings = { objects = {}, cameras = {}, lights = {}, skins = {} }
  local camera_info, light_info = file.cameras, file.lights
  for i, node in ipairs(out.nodes) do
    if node.in_scene then
      local pose = poses[i]
      if node.mesh then
        local mesh = file:mesh(node.mesh)
        local obj = c.object { mesh = mesh }
        -- a skin on a mesh without JOINTS_0 (or the reverse) poses nothing
        local skin = node.skin and mesh.skinned and node.skin or nil
        if skin and mesh.joint_count > #skins[skin] / 16 then
          error(string.format("%s: node %d ('%s'): its mesh's JOINTS_0 names joint %d, its skin %d has %d joints",
                              file.path, i - 1, node.name, mesh.joint_count - 1, skin - 1, #skins[skin] / 16), 0)
        end
        object_place(obj, pose, skin and skins[skin])
        bindings.skins[i] = skin
        add(out.objects, node.name, obj)
        bindings.objects[i] = obj
      end
      if node.camera then
        local cam = make_camera(c, camera_info[node.camera], pose)
        add(out.cameras, node.name, cam)
        out.camera_info[#out.cameras] = camera_info[node.camera]
        bindings.cameras[i] = cam
      end
      if node.light then
        local info = light_info[node.light]
        local light = make_light(c, info, pose, file.generator)
        add(out.lights, node.name, light)
        bindings.lights[i] = { light = light, kind = info.type }
      end
    end
  end
  for i, a in ipairs(file.animations) do
    add(out.animations, a.name, setmetatable({ name = a.name, start = a.start, stop = a.stop,
                                               duration = a.stop - a.start, index = i, file = file,
                                               bindings = bindings }, Animation))
  end
  --- file.bounds(): the world box of its objects where they stand now
  function out.bounds() return objects_bounds(out.objects) end
  --- file.framing_camera([fov]): a camera that frames them
  function out.framing_camera(fov)
    local b = objects_bounds(out.objects)
    return b and M.framing_camera(c, b, fov) or nil
  end
  return out
end

--- c.gltf.load(path [, { scene = name | index }]); an error points at the
--- script's line.
function M.loader(c)
  return function(path, opts)
    local ok, result = pcall(load, c, path, opts)
    if not ok then
      error((tostring(result):gsub("^[^\n]-gltf%.lua:%d+: ", "")), 2)
    end
    return result
  end
end

return M
