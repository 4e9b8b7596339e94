-- A glTF file as a scene (issue 51): c.gltf.load's objects, cameras and
-- animations against what tests/lua/gltf_reader.lua (its own JSON parser,
-- accessors, matrices and samplers) computes from the same Khronos files.
-- Placement is checked where it matters: the corners of a unit cube
-- through each object's transform against the node's world matrix.
local t = require "caustica.test"
local c = require "caustica"
local R = require "gltf_reader"

local KHRONOS = (os.getenv("CAUSTICA_ROOT") or ".") .. "/scenes/assets/khronos/"
local CORNERS = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 }, { -1, 0.5, 0.25 } }

-- The object's matrix from what the script reads (position, rotation, scale).
local function object_matrix(o)
  return R.trs(o.position, o.rotation, o.scale)
end

local function near(a, b, tol, what)
  for k = 1, #b do
    t.expect(math.abs(a[k] - b[k]) <= tol * math.max(1, math.abs(b[k])),
             string.format("%s: component %d is %.6g, the file says %.6g", what, k, a[k], b[k]))
  end
end

-- Every corner through the object's transform and through the node's world.
local function expect_placed(o, world, what)
  local m = object_matrix(o)
  for _, p in ipairs(CORNERS) do near(R.apply(m, p), R.apply(world, p), 1e-4, what) end
end

-- The nodes (0-based) with a mesh in the file's default scene, in node
-- order: the order of c.gltf.load's objects.
local function mesh_nodes(file, scene)
  local roots = file.json.scenes[(scene or file.json.scene or 0) + 1].nodes
  local parent = {}
  for i, node in ipairs(file.json.nodes) do
    for _, ch in ipairs(node.children or {}) do parent[ch] = i - 1 end
  end
  local list = {}
  for i, node in ipairs(file.json.nodes) do
    local root = i - 1
    while parent[root] do root = parent[root] end
    local inside = false
    for _, r in ipairs(roots) do inside = inside or r == root end
    if inside and node.mesh then list[#list + 1] = i - 1 end
  end
  return list
end

t.case("Cameras: the perspective and the orthographic camera where their nodes put them", function()
  local path = KHRONOS .. "Cameras/Cameras.gltf"
  local file, g = R.open(path), c.gltf.load(path)
  t.expect(#g.cameras == 2, "two cameras, got " .. #g.cameras)
  for i, cam in ipairs(g.cameras) do
    local node
    for k, n in ipairs(file.json.nodes) do if n.camera == i - 1 then node = k - 1 end end
    local w = R.world(file, node)
    local eye = R.apply(w, { 0, 0, 0 })
    local ahead = R.apply(w, { 0, 0, -1 })
    near(cam.eye, eye, 1e-5, "camera " .. i .. " eye")
    local d = { cam.target[1] - cam.eye[1], cam.target[2] - cam.eye[2], cam.target[3] - cam.eye[3] }
    near(d, { ahead[1] - eye[1], ahead[2] - eye[2], ahead[3] - eye[3] }, 1e-5, "camera " .. i .. " direction")
    local info = file.json.cameras[i]
    if info.type == "perspective" then
      t.expect(math.abs(cam.fov - math.deg(info.perspective.yfov)) < 1e-3, "fov " .. cam.fov)
      t.expect(math.abs(cam.near - info.perspective.znear) < 1e-6 and math.abs(cam.far - info.perspective.zfar) < 1e-3,
               "near and far")
      t.expect(not cam.ortho, "the perspective camera is not orthographic")
    else
      t.expect(cam.ortho and math.abs(cam.ortho.width - 2 * info.orthographic.xmag) < 1e-6,
               "the orthographic camera is 2 xmag wide")
    end
  end
  expect_placed(g.objects[1], R.world(file, 0), "the square")
  -- both render (the orthographic one too), the square on screen
  for i = 1, 2 do
    local img = t.render(KHRONOS .. "../../../tests/scenes/gltf_file.lua",
                         { set = { path = "khronos/Cameras/Cameras.gltf", camera = i, size = 64 } })
    t.expect_finite(img)
    local lit = 0
    for y = 0, 63 do for x = 0, 63 do if img:pixel(x, y) > 0.05 then lit = lit + 1 end end end
    t.expect(lit > 200, string.format("camera %d sees the square: %d lit pixels", i, lit))
  end
end)

t.case("MultipleScenes: `scene` picks which nodes become objects", function()
  local path = KHRONOS .. "MultipleScenes/MultipleScenes.gltf"
  local file = R.open(path)
  for scene = 0, 1 do
    local g = c.gltf.load(path, { scene = scene })
    local nodes = mesh_nodes(file, scene)
    t.expect(#g.objects == #nodes, string.format("scene %d: %d objects, the file has %d", scene, #g.objects, #nodes))
    t.expect(g.objects[1].mesh.vertex_count > 0, "a mesh")
    for k, n in ipairs(nodes) do expect_placed(g.objects[k], R.world(file, n), "scene " .. scene) end
  end
  local a, b = c.gltf.load(path, { scene = 0 }), c.gltf.load(path, { scene = 1 })
  t.expect(a.objects[1].mesh.vertex_count ~= b.objects[1].mesh.vertex_count,
           "the two scenes hold different meshes (a square and a triangle)")
  local ok, err = pcall(c.gltf.load, path, { scene = 5 })
  t.expect(not ok and err:find("MultipleScenes.gltf: no scene 5 %(the file has 2, numbered from 0%)"), tostring(err))
  ok, err = pcall(c.gltf.load, path, { scene = "Kitchen" })
  t.expect(not ok and err:find("no scene named 'Kitchen'"), tostring(err))
end)

-- Animation `anim` (0-based) of `path`, its objects at each time against
-- the reader's nodes.
local function check_animation(path, anim, times)
  local file, g = R.open(path), c.gltf.load(path)
  local nodes = mesh_nodes(file)
  local a = g.animations[anim + 1]
  for _, time in ipairs(times) do
    a:apply(time - a.start, { loop = false })
    local override, weights = R.pose(file, anim, time)
    for k, n in ipairs(nodes) do
      local what = string.format("%s, animation '%s' at %g s, node %d", path:match("[^/]+$"), a.name, time, n)
      expect_placed(g.objects[k], R.world(file, n, override), what)
      if weights[n] then near(g.objects[k].morph_weights, weights[n], 1e-5, what .. " weights") end
    end
  end
  return g, file
end

t.case("BoxAnimated: at its keyframes and between", function()
  -- keys: rotation 1.25 and 2.5 s, translation 0, 1.25, 2.5, 3.708 s
  check_animation(KHRONOS .. "BoxAnimated/BoxAnimated.glb", 0, { 0, 0.4, 1.25, 1.6, 1.875, 2.5, 3.1, 3.708, 6 })
end)

t.case("AnimatedTriangle: at its keyframes and between", function()
  check_animation(KHRONOS .. "AnimatedTriangle/AnimatedTriangle.gltf", 0, { 0, 0.1, 0.25, 0.5, 0.66, 0.75, 1.0 })
end)

t.case("InterpolationTest: every cube where its STEP, LINEAR or CUBICSPLINE sampler puts it", function()
  local path = KHRONOS .. "InterpolationTest/InterpolationTest.glb"
  local file = R.open(path)
  local kinds = {}
  for anim = 0, #file.json.animations - 1 do
    local a = file.json.animations[anim + 1]
    kinds[#kinds + 1] = a.samplers[1].interpolation
    local times = R.accessor(file, a.samplers[1].input)
    local list = {}
    for k = 1, #times - 1 do
      local t0, t1 = times[k][1], times[k + 1][1]
      list[#list + 1] = t0
      list[#list + 1] = t0 + 0.3 * (t1 - t0)
      list[#list + 1] = t0 + 0.77 * (t1 - t0)
    end
    list[#list + 1] = times[#times][1]
    check_animation(path, anim, list)
  end
  local seen = table.concat(kinds, " ")
  t.expect(seen:find("STEP") and seen:find("LINEAR") and seen:find("CUBICSPLINE"), "all three samplers: " .. seen)
end)

t.case("AnimatedMorphCube and SimpleMorph: morph weights at keys and between", function()
  local g = check_animation(KHRONOS .. "AnimatedMorphCube/AnimatedMorphCube.glb", 0, { 0, 0.5, 1.0, 1.37, 2.0, 3.0 })
  t.expect(#g.objects[1].morph_weights == 2, "two weights")
  check_animation(KHRONOS .. "SimpleMorph/SimpleMorph.gltf", 0, { 0, 0.5, 1.0, 1.5, 2.2, 3.0, 4.0 })
end)

t.case("an animation loops by default and holds its last key with loop = false", function()
  local path = KHRONOS .. "BoxAnimated/BoxAnimated.glb"
  local g = c.gltf.load(path)
  local a = g.animations[1]
  a:apply(1.0)
  local p1 = g.objects[1].position
  a:apply(1.0 + a.duration)
  near(g.objects[1].position, p1, 1e-5, "one period later")
  a:apply(a.duration, { loop = false })
  local last = g.objects[1].position
  a:apply(a.duration + 5, { loop = false })
  near(g.objects[1].position, last, 1e-5, "held")
end)

-- Skins: the GPU's skinned mesh (deform.comp) against gltf_reader's own
-- skinning of the file, as silhouettes: flat white through an orthographic
-- camera down -z (tests/scenes/gltf_silhouette.lua), 64 x 64, pixel
-- centres inside a skinned triangle. Each time is checked to pose the mesh
-- far from its bind pose first, so that a skin not applied fails.
local function skinned_node(file)
  for i, node in ipairs(file.json.nodes) do
    if node.skin and node.mesh then return i - 1 end
  end
end

local function mismatch(a, b, size)
  local n, inside = 0, 0
  for y = 1, size do
    for x = 1, size do
      if (a[y][x] or false) ~= (b[y][x] or false) then n = n + 1 end
      if a[y][x] then inside = inside + 1 end
    end
  end
  return n, inside
end

local function check_skin(name, times)
  local rel = "khronos/" .. name .. "/" .. name .. ".glb"
  local path = KHRONOS .. name .. "/" .. name .. ".glb"
  local file = R.open(path)
  local n = skinned_node(file)
  local size = 64
  for _, time in ipairs(times) do
    local tris = R.skinned_triangles(file, n, 0, time)
    local lo, hi = { math.huge, math.huge }, { -math.huge, -math.huge }
    for _, tri in ipairs(tris) do
      for _, p in ipairs(tri) do
        lo = { math.min(lo[1], p[1]), math.min(lo[2], p[2]) }
        hi = { math.max(hi[1], p[1]), math.max(hi[2], p[2]) }
      end
    end
    local cx, cy = (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2
    local width = 1.15 * math.max(hi[1] - lo[1], hi[2] - lo[2])
    local want = R.silhouette(tris, cx, cy, width, size)
    local img = t.render("tests/scenes/gltf_silhouette.lua",
                         { set = { path = rel, time = time, cx = cx, cy = cy, width = width, size = size } })
    t.expect_finite(img)
    local got = {}
    for y = 1, size do
      got[y] = {}
      for x = 1, size do got[y][x] = img:pixel(x - 1, y - 1) > 0.1 or nil end
    end
    local wrong, inside = mismatch(want, got, size)
    local bound = math.max(3, math.floor(0.01 * inside)) -- edge pixels: rasterisation rules
    -- the bind pose (every joint matrix the identity) seen the same way
    local rest = {}
    for _, prim in ipairs(file.json.meshes[file.json.nodes[n + 1].mesh + 1].primitives) do
      local pos, idx = R.accessor(file, prim.attributes.POSITION), R.accessor(file, prim.indices)
      for k = 1, #idx, 3 do
        rest[#rest + 1] = { pos[idx[k][1] + 1], pos[idx[k + 1][1] + 1], pos[idx[k + 2][1] + 1] }
      end
    end
    local unposed = mismatch(want, R.silhouette(rest, cx, cy, width, size), size)
    print(string.format("%s at %g s: %d of %d silhouette pixels differ (bound %d); unskinned %d", name, time, wrong,
                        inside, bound, unposed))
    t.expect(unposed > 3 * bound, string.format("%s at %g s: the pose differs from the bind pose (%d pixels)", name,
                                                time, unposed))
    t.expect(wrong <= bound, string.format("%s at %g s: %d of %d silhouette pixels differ from the file's skinning "
                                           .. "(at most %d)", name, time, wrong, inside, bound))
  end
end

t.case("RiggedSimple and CesiumMan: the skinned mesh where the file's joints put it, at two times", function()
  check_skin("RiggedSimple", { 0.5, 2.1 })
  check_skin("CesiumMan", { 0.4, 1.3 })
end)

-- Blender as the client: scenes/assets/make_blender_scene.py builds a
-- scene in Blender 3.4 and exports it with Blender's own glTF exporter
-- (blender_scene.glb), and renders it through its camera with Cycles
-- (blender_scene_cycles.png, 160 x 120, frame 1). caustica renders the file
-- with no script (its camera, lights, animations): the red cube and the
-- green rod must stand where Blender's render has them.
local function centroid(img, w, h, test)
  local sx, sy, n = 0, 0, 0
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local r, g, b = img:pixel(x, y)
      if test(r, g, b) then sx, sy, n = sx + x, sy + y, n + 1 end
    end
  end
  return n > 0 and { sx / n, sy / n } or nil, n
end
local function red(r, g, b) return r > 0.15 and r > 4 * g and r > 4 * b end
local function green(r, g, b) return g > 0.08 and g > 2 * r and g > 2 * b end

t.case("a scene made and exported by Blender renders with Blender's camera framing", function()
  local root = (os.getenv("CAUSTICA_ROOT") or ".") .. "/scenes/assets/"
  local blender = c.image.load(root .. "blender_scene_cycles.png")
  local mine = t.render(root .. "blender_scene.glb", { size = { 160, 120 } })
  t.expect_finite(mine)
  for _, part in ipairs { { "the red cube", red }, { "the green rod", green } } do
    local want, nw = centroid(blender, 160, 120, part[2])
    local got, ng = centroid(mine, 160, 120, part[2])
    t.expect(want and got, string.format("%s is in both images (%d and %d pixels)", part[1], nw, ng))
    local d = math.sqrt((want[1] - got[1]) ^ 2 + (want[2] - got[2]) ^ 2)
    print(string.format("%s: Blender's at (%.1f, %.1f), %d px; caustica's at (%.1f, %.1f), %d px: %.2f px apart",
                        part[1], want[1], want[2], nw, got[1], got[2], ng, d))
    t.expect(d < 1.5, string.format("%s: %.2f pixels from where Blender draws it (at most 1.5)", part[1], d))
    t.expect(math.abs(ng - nw) < 0.25 * nw, string.format("%s: %d pixels against Blender's %d", part[1], ng, nw))
  end
end)

t.case("KHR_lights_punctual: kinds, units, cones and where the nodes point them", function()
  local root = (os.getenv("CAUSTICA_ROOT") or ".") .. "/tests/data/"
  local f = c.gltf.load(root .. "lights.gltf")
  t.expect(#f.lights == 3, "three lights")
  local sun, bulb, spot = f.lights.SunNode, f.lights.BulbNode, f.lights.SpotNode
  -- lux and candela over 683 lm/W, times the colour
  near(sun.intensity, { 3 / 683, 1.5 / 683, 0.75 / 683 }, 1e-6, "the sun's W/m^2")
  near(sun.direction, { 0, -1, 0 }, 1e-5, "the sun along its node's -z")
  near(bulb.intensity, { 1, 1, 1 }, 1e-6, "683 cd: 1 W/sr")
  near(bulb.position, { 1, 2, 3 }, 1e-6, "the bulb where its node is")
  near(spot.intensity, { 2, 2, 2 }, 1e-6, "1366 cd: 2 W/sr")
  near(spot.direction, { -1, 0, 0 }, 1e-5, "the spot along its node's -z")
  t.expect(math.abs(spot.angle - math.deg(0.4)) < 1e-3, "the outer cone: " .. spot.angle)
  t.expect(math.abs(spot.softness - 0.5) < 1e-5, "softness (outer - inner) / outer: " .. spot.softness)
  -- Blender's exporter writes a sun's W/m^2 as lux without the 683
  local b = c.gltf.load(root .. "lights_blender.gltf")
  near(b.lights.SunNode.intensity, { 3, 1.5, 0.75 }, 1e-6, "a Blender sun's W/m^2")
  near(b.lights.BulbNode.intensity, { 1, 1, 1 }, 1e-6, "a Blender point light as any other")
end)
