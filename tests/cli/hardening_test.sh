# Hardening (issue 9): each reproducer of a sandbox escape, a crash or a hang
# is refused with a one-line error (exit 1) and writes nothing, or, where
# the input is legal, renders without a crash.
source "$(dirname "$0")/lib.sh"
O="$WORK/out.png"

# scene NAME BODY: a script in $WORK that runs BODY, then returns a tiny
# environment-only frame (so that what BODY does is all that is tested).
scene() {
  cat >"$WORK/$1.lua" <<EOF
local c = require "caustica"
local dir = c.param("dir", "")
$2
local scene = c.scene {}
local g = c.graph()
g:add("env", c.pass.environment {})
g:output("env.color")
return { scene = scene, graph = g, size = {8, 8} }
EOF
}

# ---- the sandbox: writing -------------------------------------------------
rm -f /tmp/caustica-escape-save.png
scene save_anywhere 'c.image.new(4, 4):save("/tmp/caustica-escape-save.png")'
expect_error "image:save to an absolute path" 1 "save_anywhere.lua:3:" "/tmp/caustica-escape-save.png" -- \
  "$CAUSTICA" render "$WORK/save_anywhere.lua" -o "$O"

mkdir -p "$WORK/tree" && echo original >"$WORK/tree/Makefile"
scene rewrite 'local f = io.open("Makefile", "w") f:write("pwned") f:close()'
(cd "$WORK/tree" && "$CAUSTICA" render "$WORK/rewrite.lua" -o out.png 2>"$WORK/err")
rc=$?
if [ $rc = 1 ] && [ "$(cat "$WORK/tree/Makefile")" = original ] && grep -q "may not write" "$WORK/err"; then
  pass "render with the default -o cannot rewrite ./Makefile"
else
  fail "render with the default -o cannot rewrite ./Makefile" "exit $rc, Makefile: $(cat "$WORK/tree/Makefile"), $(head -1 "$WORK/err")"
fi

mkdir -p "$WORK/rec"
scene parent_write 'io.open(dir .. "/../escaped.txt", "w")'
expect_error "record may not write beside its folder" 1 "may write only inside" "$WORK/escaped.txt" -- \
  "$CAUSTICA" record "$WORK/parent_write.lua" -o "$WORK/rec" --set dir="$WORK/rec"

mkdir -p "$WORK/elsewhere"
ln -s "$WORK/elsewhere/target.txt" "$WORK/rec/link"
ln -s "$WORK/elsewhere" "$WORK/rec/linkdir"
scene link_write 'local f = assert(io.open(dir .. "/link", "w")) f:write("x") f:close()'
expect_error "no write through a link in the output folder" 1 "symbolic link" "$WORK/elsewhere/target.txt" -- \
  "$CAUSTICA" record "$WORK/link_write.lua" -o "$WORK/rec" --set dir="$WORK/rec"
scene linkdir_write 'local f = assert(io.open(dir .. "/linkdir/f.txt", "w")) f:write("x") f:close()'
expect_error "no write into a linked folder" 1 "may write only inside" "$WORK/elsewhere/f.txt" -- \
  "$CAUSTICA" record "$WORK/linkdir_write.lua" -o "$WORK/rec" --set dir="$WORK/rec"
rm -f "$WORK/rec/link" "$WORK/rec/linkdir"

scene own_write 'local f = assert(io.open(dir .. "/note.txt", "w")) f:write("x") f:close()'
"$CAUSTICA" record "$WORK/own_write.lua" -o "$WORK/rec" --set dir="$WORK/rec" >/dev/null 2>"$WORK/err" \
  && test -f "$WORK/rec/note.txt" && pass "record may write inside its folder" \
  || fail "record may write inside its folder" "$(head -1 "$WORK/err")"
mkdir -p "$WORK/allowed"
scene allowed_write 'local f = assert(io.open(dir .. "/note.txt", "w")) f:write("x") f:close()'
"$CAUSTICA" render "$WORK/allowed_write.lua" -o "$O" --allow-write "$WORK/allowed" --set dir="$WORK/allowed" \
  2>"$WORK/err" && test -f "$WORK/allowed/note.txt" && pass "--allow-write DIR opens a folder" \
  || fail "--allow-write DIR opens a folder" "$(head -1 "$WORK/err")"
rm -f "$O"

# ---- the sandbox: binary chunks, by every route ----------------------------
scene dump 'local f = assert(io.open(dir .. "/m.lua", "wb")) f:write(string.dump(function() return 1 end)) f:close()'
"$CAUSTICA" record "$WORK/dump.lua" -o "$WORK/rec" --set dir="$WORK/rec" >/dev/null 2>&1
test -s "$WORK/rec/m.lua" && pass "(a binary chunk was written for the next cases)" || fail "binary chunk" "not written"
scene require_binary 'package.path = dir .. "/?.lua"; require "m"'
expect_error "require refuses a binary chunk" 1 "binary chunk" - -- \
  "$CAUSTICA" record "$WORK/require_binary.lua" -o "$WORK/rec2" --set dir="$WORK/rec"
scene loadfile_binary 'assert(loadfile(dir .. "/m.lua"))'
expect_error "loadfile refuses a binary chunk" 1 "binary chunk" - -- \
  "$CAUSTICA" record "$WORK/loadfile_binary.lua" -o "$WORK/rec2" --set dir="$WORK/rec"
scene dofile_binary 'dofile(dir .. "/m.lua")'
expect_error "dofile refuses a binary chunk" 1 "binary chunk" - -- \
  "$CAUSTICA" record "$WORK/dofile_binary.lua" -o "$WORK/rec2" --set dir="$WORK/rec"
scene searcher_binary 'table.insert(package.searchers, 1, function(name)
  local f = io.open(dir .. "/m.lua", "rb") local bytes = f:read("a") f:close()
  return assert(load(bytes)) end); require "anything"'
expect_error "a searcher of the script's own refuses a binary chunk" 1 "binary chunk" - -- \
  "$CAUSTICA" record "$WORK/searcher_binary.lua" -o "$WORK/rec2" --set dir="$WORK/rec"
scene load_binary 'assert(load(string.dump(function() end)))'
expect_error "load refuses a binary chunk" 1 "binary chunk" "$O" -- "$CAUSTICA" render "$WORK/load_binary.lua" -o "$O"

# ---- the sandbox: metatables and early __gc --------------------------------
scene gc_early 'local ball = c.object { mesh = c.mesh.sphere {} }
getmetatable(ball).__gc(ball)'
expect_error "userdata metatables are protected" 1 "gc_early.lua:4:" "$O" -- \
  "$CAUSTICA" render "$WORK/gc_early.lua" -o "$O"
for what in object mesh light scene graph pass environment medium; do
  cat >"$WORK/gc_$what.lua" <<EOF
local c = require "caustica"
local scene = c.scene { environment = c.cubemap "$ROOT/scenes/assets/env/room",
                        medium = c.medium { sigma_s = {0.1, 0.1, 0.1}, box = {{-1, -1, -1}, {1, 1, 1}} } }
local mesh = c.mesh.sphere {}
local ball = scene:add(c.object { mesh = mesh, position = {0, 0.5, 0} })
local lamp = scene:add(c.light.point { position = {1, 2, 1} })
local g = c.graph()
local shadow = g:add("shadow", c.pass.shadow_map { light = lamp, size = 64 })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
local victims = { object = ball, mesh = mesh, light = lamp, scene = scene, graph = g, pass = shadow,
                  environment = scene.environment, medium = scene.medium }
local v = victims["$what"]
debug.getmetatable(v).__gc(v)
debug.getmetatable(v).__gc(v) -- twice: idempotent
collectgarbage()
return { scene = scene, graph = g, size = {16, 16} }
EOF
  "$CAUSTICA" render "$WORK/gc_$what.lua" --trusted -o "$O" >/dev/null 2>"$WORK/err"
  rc=$?
  if [ $rc -le 1 ] && ! grep -qiE "segmentation|abort|sanitizer" "$WORK/err"; then
    pass "a $what released early by a trusted script: no crash (exit $rc)"
  else
    fail "a $what released early" "exit $rc: $(head -3 "$WORK/err")"
  fi
done
rm -f "$O"

# ---- the sandbox: reading ------------------------------------------------
scene read_shadow 'io.open("/etc/passwd"):read("a")'
expect_error "reading outside the allowed folders" 1 "may read only" "$O" -- \
  "$CAUSTICA" render "$WORK/read_shadow.lua" -o "$O"
scene read_lines 'for l in io.lines("/etc/passwd") do end'
expect_error "io.lines outside the allowed folders" 1 "may read only" "$O" -- \
  "$CAUSTICA" render "$WORK/read_lines.lua" -o "$O"
scene read_mesh 'c.mesh.load "/etc/passwd"'
expect_error "a mesh from outside the allowed folders" 1 "may read only" "$O" -- \
  "$CAUSTICA" render "$WORK/read_mesh.lua" -o "$O"
scene read_texture 'c.texture "/etc/passwd"'
expect_error "a texture from outside the allowed folders" 1 "may read only" "$O" -- \
  "$CAUSTICA" render "$WORK/read_texture.lua" -o "$O"
scene read_texture_table 'c.texture { file = "/etc/passwd" }'
expect_error "a texture (option table) from outside the allowed folders" 1 "may read only" "$O" -- \
  "$CAUSTICA" render "$WORK/read_texture_table.lua" -o "$O"
scene getenv 'print(os.getenv("HOME"))'
expect_error "no environment variables" 1 "os.getenv is not available" "$O" -- \
  "$CAUSTICA" render "$WORK/getenv.lua" -o "$O"
echo "return 42" >"$WORK/mine.lua"
scene read_own 'assert(dofile("'"$WORK"'/mine.lua") == 42); assert(io.open("'"$WORK"'/mine.lua")):close()
local ok = c.mesh.load "'"$ROOT"'/scenes/assets/teapot.glb"'
"$CAUSTICA" render "$WORK/read_own.lua" -o "$O" 2>"$WORK/err" && pass "the script's folder and the project's assets are readable" \
  || fail "own folder readable" "$(head -1 "$WORK/err")"
echo "return 42" >"$WORK/elsewhere/other.lua"
scene read_allowed 'assert(dofile("'"$WORK"'/elsewhere/other.lua") == 42)'
mkdir -p "$WORK/sub" && mv "$WORK/read_allowed.lua" "$WORK/sub/"
"$CAUSTICA" render "$WORK/sub/read_allowed.lua" -o "$O" --allow-read "$WORK/elsewhere" 2>"$WORK/err" \
  && pass "--allow-read DIR opens a folder" || fail "--allow-read" "$(head -1 "$WORK/err")"
rm -f "$O"

# ---- crashes and hangs ----------------------------------------------------
printf 'local c = require "caustica"\nreturn { scene = c.scene {}, graph = c.graph(), size = "64x64" }\n' >"$WORK/size_string.lua"
expect_error "size as a string" 1 "'size' must be {width, height}" "$O" -- "$CAUSTICA" render "$WORK/size_string.lua" -o "$O"
printf 'local c = require "caustica"\nreturn { scene = c.scene {}, graph = c.graph(), size = 64 }\n' >"$WORK/size_number.lua"
expect_error "size as a number" 1 "'size' must be {width, height}" "$O" -- "$CAUSTICA" render "$WORK/size_number.lua" -o "$O"
printf 'local c = require "caustica"\nreturn { scene = c.scene {}, graph = c.graph(), frames = 0/0 }\n' >"$WORK/frames_nan.lua"
expect_error "frames = NaN" 1 "'frames' must be a finite number" "$WORK/rec3" -- \
  "$CAUSTICA" record "$WORK/frames_nan.lua" -o "$WORK/rec3"
expect_error "--frame far past the script's frames" 1 "past the script's last frame" "$O" -- \
  "$CAUSTICA" render scenes/demo.lua --frame 1000000000 -o "$O"

cat >"$WORK/adds_passes.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("fill", c.pass.custom { outputs = { color = "rgba32f" }, run = function(ctx)
  for i = 1, 100 do g:add("more" .. i, c.pass.environment {}) end
  collectgarbage()
end })
g:output("fill.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
expect_error "a custom pass adding passes while the graph runs" 1 "the graph is rendering a frame" "$O" -- \
  "$CAUSTICA" render "$WORK/adds_passes.lua" -o "$O"

scene render_self 'c.image.render("'"$WORK"'/render_self.lua")'
expect_error "a sandboxed script may not start renders" 1 "c.image.render is not available to a sandboxed" "$O" -- \
  "$CAUSTICA" render "$WORK/render_self.lua" -o "$O"
expect_error "a trusted script rendering itself" 1 "nest deeper than" "$O" -- \
  "$CAUSTICA" render "$WORK/render_self.lua" -o "$O" --trusted
cat >"$WORK/collects.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("fill", c.pass.custom { outputs = { color = "rgba32f" }, run = function(ctx)
  collectgarbage() collectgarbage()
  ctx:clear("color", {0.5, 0.5, 0.5, 1})
end })
g:output("fill.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
"$CAUSTICA" render "$WORK/collects.lua" -o "$O" 2>"$WORK/err" && pass "a custom pass that collects garbage while the graph runs" \
  || fail "collect in run" "$(head -1 "$WORK/err")"
rm -f "$O"

scene loop_top 'while true do end'
expect_error "an endless loop at top level" 1 "loop_top.lua:3: script ran longer than 1 s" "$O" -- \
  "$CAUSTICA" render "$WORK/loop_top.lua" -o "$O" --script-timeout 1
scene loop_pcall 'while true do pcall(function() while true do end end) end'
expect_error "an endless loop that catches the timeout" 1 "script ran longer than 1 s" "$O" -- \
  "$CAUSTICA" render "$WORK/loop_pcall.lua" -o "$O" --script-timeout 1
cat >"$WORK/loop_update.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("env", c.pass.environment {})
g:output("env.color")
return { scene = c.scene {}, graph = g, size = {8, 8}, frames = 10,
         update = function(t, dt) if t > 0.1 then while true do end end end }
EOF
expect_error "an endless loop in update" 1 "script ran longer than 1 s (raise --script-timeout, 0 = no limit) (in update, frame 4)" \
  "$O" -- "$CAUSTICA" render "$WORK/loop_update.lua" --frame 6 -o "$O" --script-timeout 1
cat >"$WORK/loop_pass.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("fill", c.pass.custom { outputs = { color = "rgba32f" }, run = function(ctx) while true do end end })
g:output("fill.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
expect_error "an endless loop in a custom pass" 1 "(in run of custom pass 'fill')" "$O" -- \
  "$CAUSTICA" render "$WORK/loop_pass.lua" -o "$O" --script-timeout 1
scene bomb 'local t = {} for i = 1, 1e9 do t[i] = {i, i, i} end'
expect_error "a table bomb" 1 "the script used more than 64 MB" "$O" -- \
  "$CAUSTICA" render "$WORK/bomb.lua" -o "$O" --script-memory 64
scene string_bomb 'local s = "x" for i = 1, 40 do s = s .. s end'
expect_error "a string bomb" 1 "the script used more than 64 MB" "$O" -- \
  "$CAUSTICA" render "$WORK/string_bomb.lua" -o "$O" --script-memory 64

scene shadow_size_zero 'c.pass.shadow_map { light = c.light.point {}, size = 0 }'
expect_error "an out-of-range pass parameter names its range" 1 "bad argument 'size' to 'shadow_map' (0 is out of range" \
  "$O" -- "$CAUSTICA" render "$WORK/shadow_size_zero.lua" -o "$O"
scene segments_float 'c.mesh.sphere { segments = 1e9 }'
expect_error "a float where an integer goes" 1 "bad argument 'segments' to 'sphere' (integer expected, got 1e+09)" \
  "$O" -- "$CAUSTICA" render "$WORK/segments_float.lua" -o "$O"
scene segments_wrap 'c.mesh.sphere { segments = 4294967328 }'
expect_error "an integer that does not fit" 1 "got 4294967328, which does not fit" "$O" -- \
  "$CAUSTICA" render "$WORK/segments_wrap.lua" -o "$O"
for bad in "damping = -100" "depth = -1" "wave_speed = 0" "wave_speed = 1/0" "wave_speed = 0/0"; do
  scene water_bad "c.water { $bad }"
  expect_error "c.water { $bad } says why" 1 "water" "$O" -- "$CAUSTICA" render "$WORK/water_bad.lua" -o "$O"
  grep -q "out of memory" "$WORK/stderr" && fail "c.water { $bad }" "says out of memory"
done
mkdir -p "$WORK/shader.frag"
cat >"$WORK/shader_dir.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("full", c.pass.fullscreen { shader = "shader.frag" })
g:output("full.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
expect_error "a shader path that is a folder" 1 "it is a folder" "$O" -- "$CAUSTICA" render "$WORK/shader_dir.lua" -o "$O"
printf '#version 450 core\nout vec4 color;\nvoid main() { color = vec4(1.0); }\n' >"$WORK/flat.frag"
cat >"$WORK/context_error.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
local errors = 0
g:add("fill", c.pass.custom { outputs = { color = "rgba32f" }, run = function(ctx)
  for i = 1, 200 do
    if not pcall(ctx.fullscreen, ctx, { shader = "flat.frag", output = "color", inputs = { image = "nosuch" } }) then
      errors = errors + 1
    end
  end
  assert(errors == 200)
  ctx:clear("color", {0.5, 0.5, 0.5, 1})
end })
g:output("fill.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
"$CAUSTICA" render "$WORK/context_error.lua" -o "$O" 2>"$WORK/err" \
  && pass "a pass context that raised errors keeps working" || fail "pass context errors" "$(head -2 "$WORK/err")"
rm -f "$O"

# ---- output ---------------------------------------------------------------
mkdir -p "$WORK/frames"
touch "$WORK/frames/.frame_0004.png.caustica-tmp.999999999" "$WORK/frames/.frame_0005.png.caustica-tmp.$$" \
  "$WORK/frames/.frame_0006.png.caustica-tmp.999999999.Ab3xYz"
"$CAUSTICA" record scenes/demo.lua -o "$WORK/frames" --frames 0:1 --size 16x16 >/dev/null 2>&1
if [ ! -e "$WORK/frames/.frame_0004.png.caustica-tmp.999999999" ] && [ -e "$WORK/frames/.frame_0005.png.caustica-tmp.$$" ] &&
   [ ! -e "$WORK/frames/.frame_0006.png.caustica-tmp.999999999.Ab3xYz" ]; then
  pass "a killed run's temporaries are removed, a running writer's kept"
else
  fail "stale temporaries" "$(ls -a "$WORK/frames")"
fi
# SIGKILL mid-record, then a second run: nothing of the first run stays behind.
"$CAUSTICA" record scenes/demo.lua -o "$WORK/killed" --frames 0:200 --size 64x64 >/dev/null 2>&1 &
pid=$!
sleep 2
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
"$CAUSTICA" record scenes/demo.lua -o "$WORK/killed" --frames 0:0 --size 16x16 >/dev/null 2>&1
leftovers=$(ls -a "$WORK/killed" | grep -cE 'caustica-tmp|\.tmp\.')
[ "$leftovers" = 0 ] && pass "record killed with SIGKILL leaves nothing after the next run" \
  || fail "SIGKILL leftovers" "$(ls -a "$WORK/killed")"

# A write that fails (the file size limit stands in for a full disk: the
# same short write, EFBIG instead of ENOSPC).
(ulimit -f 1; trap '' XFSZ; exec "$CAUSTICA" render scenes/demo.lua --size 256x256 -o "$WORK/big.png") 2>"$WORK/err"
rc=$?
first=$(head -1 "$WORK/err")
if [ $rc = 1 ] && grep -q "big.png: write failed: File too large" <<<"$first" && ! grep -q "libpng error" "$WORK/err" \
   && ! ls -a "$WORK" | grep -q "big.png"; then
  pass "a failed PNG write says why in caustica's words and leaves nothing"
else
  fail "failed PNG write" "exit $rc: $first"
fi
(ulimit -f 1; trap '' XFSZ; exec "$CAUSTICA" render scenes/demo.lua --size 256x256 -o "$WORK/big.pfm") 2>"$WORK/err"
rc=$?
first=$(head -1 "$WORK/err")
[ $rc = 1 ] && grep -q "big.pfm: write failed: File too large" <<<"$first" && pass "a failed PFM write says why" \
  || fail "failed PFM write" "exit $rc: $first"

# NaN from a shader is never written: counted in a warning, written as 0.
printf '#version 450 core\nout vec4 color;\nuniform float zero;\nvoid main() { color = vec4(zero / zero, 1.0 / zero, 0.5, 1.0); }\n' >"$WORK/nan.frag"
cat >"$WORK/nan.lua" <<'EOF'
local c = require "caustica"
local g = c.graph()
g:add("full", c.pass.fullscreen { shader = "nan.frag", uniforms = { zero = 0 } })
g:output("full.color")
return { scene = c.scene {}, graph = g, size = {8, 8} }
EOF
"$CAUSTICA" render "$WORK/nan.lua" -o "$WORK/nan.pfm" 2>"$WORK/err"
line=$("$CAUSTICA" compare "$WORK/nan.pfm" "$WORK/nan.pfm" 2>&1)
if grep -q "64 pixels had NaN or Inf values, written as 0" "$WORK/err" && [ "$(metric nan "$line")" = 0 ]; then
  pass "NaN and Inf are never written (counted in a warning)"
else
  fail "NaN in output" "$(head -1 "$WORK/err") / $line"
fi
# Issue 31: a reader's suffix ("x.exr:layer") does not carry a read out of the sandbox: the file
# that is opened is what is checked, and a path whose folder does not exist is refused.
mkdir -p "$WORK/outside" "$WORK/inside"
"$CAUSTICA" convert scenes/assets/env/sky.hdr "$WORK/outside/secret.exr" >/dev/null 2>&1
printf 'local c = require "caustica"\nlocal img = c.image.load(c.param("path", ""))\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/inside/peek.lua"
for p in "$WORK/outside/secret.exr:a/b" "$WORK/outside/secret.exr:x/y.exr" "$WORK/outside/secret.exr"; do
  expect_error "no read outside the sandbox through '${p#$WORK/}'" 1 "a sandboxed scene script may read only" - -- \
    "$CAUSTICA" render "$WORK/inside/peek.lua" --set path="$p" -o "$WORK/x.png"
done
printf 'local c = require "caustica"\nlocal e = c.cubemap(c.param("path", ""))\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/inside/cube.lua"
expect_error "no cube map outside the sandbox through a layer suffix" 1 "a sandboxed scene script may read only" - -- \
  "$CAUSTICA" render "$WORK/inside/cube.lua" --set path="$WORK/outside/secret.exr:a/b.exr" -o "$WORK/x.png"
expect_error "a path whose folder does not exist is refused, not waved through" 1 "no such file (its folder does not exist)" - -- \
  "$CAUSTICA" render "$WORK/inside/peek.lua" --set path="$WORK/nowhere/at/all.exr" -o "$WORK/x.png"
"$CAUSTICA" render "$WORK/inside/peek.lua" --set path="$WORK/outside/secret.exr:a/b" --allow-read "$WORK/outside" \
  -o "$WORK/x.png" 2>"$WORK/err"
grep -q "no layer 'a/b'" "$WORK/err" && pass "with --allow-read the layer is looked up (and missing)" || fail "allowed read" "$(cat "$WORK/err")"
# Shared folders (issue 31): a cache entry planted as a link is replaced, never written through; a
# FIFO where an image or a cache entry should be is refused at once instead of blocking.
mkdir -p "$WORK/shared"
echo "someone else's file" >"$WORK/victim.txt"
cat >"$WORK/shared/still.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
scene:add(c.light.directional { direction = {0.2, -1, -0.3}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass {} })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {16, 16} }
EOF
"$CAUSTICA" bench "$WORK/shared/still.lua" --sweep shade.specular=true,false --frames 1 --ref-photons 2000 \
  -o "$WORK/shared/b" -q >/dev/null 2>&1
truth=$(ls "$WORK"/shared/b/cache/truth_*[0-9a-f].pfm 2>/dev/null | head -1)
if [ -n "$truth" ]; then
  rm -f "$truth" && ln -s "$WORK/victim.txt" "$truth"
  "$CAUSTICA" bench "$WORK/shared/still.lua" --sweep shade.specular=true,false --frames 1 --ref-photons 2000 \
    -o "$WORK/shared/b" -q >/dev/null 2>"$WORK/err"
  grep -q "a cached truth that is not a regular file (a link, a FIFO): refused" "$WORK/err" &&
    [ "$(cat "$WORK/victim.txt")" = "someone else's file" ] \
    && pass "a cached truth planted as a link is refused, its target untouched" || fail "truth link" "$(cat "$WORK/err")"
  rm -f "$truth"
  mkfifo "$truth"
  timeout 20 "$CAUSTICA" bench "$WORK/shared/still.lua" --sweep shade.specular=true,false --frames 1 --ref-photons 2000 \
    -o "$WORK/shared/b" -q >/dev/null 2>"$WORK/err"
  rc=$?
  [ $rc = 1 ] && grep -q "refused" "$WORK/err" && pass "a FIFO at a cached truth: refused at once (no block)" \
    || fail "truth FIFO" "exit $rc: $(cat "$WORK/err")"
  rm -f "$truth"
else
  fail "bench cache" "no cached truth"
fi
# --video: ffmpeg writes its list and its output by name; links planted at the names a video used to
# be encoded through (the list beside the output, a hidden temporary) are never written through.
if command -v ffmpeg >/dev/null 2>&1; then
  mkdir -p "$WORK/shared/vid"
  ln -s "$WORK/victim_list" "$WORK/shared/vid/v.mp4.frames.txt"
  ln -s "$WORK/victim_video" "$WORK/shared/vid/.v.mp4.caustica-tmp.mp4"
  "$CAUSTICA" record "$WORK/shared/still.lua" --frame-count 2 -o "$WORK/shared/vid/f.png" \
    --video "$WORK/shared/vid/v.mp4" -q >/dev/null 2>"$WORK/err"
  [ -s "$WORK/shared/vid/v.mp4" ] && [ ! -e "$WORK/victim_list" ] && [ ! -e "$WORK/victim_video" ] &&
    [ "$(ls -A "$WORK/shared/vid" | grep -c caustica-tmp)" = 1 ] \
    && pass "--video: links planted at its old temporary names are not written through, nothing left" \
    || fail "video links" "$(ls -la "$WORK/shared/vid"; cat "$WORK/err")"
fi
mkfifo "$WORK/shared/pipe.pfm"
printf 'local c = require "caustica"\nlocal img = c.image.load("pipe.pfm")\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/shared/fifo.lua"
timeout 20 "$CAUSTICA" render "$WORK/shared/fifo.lua" -o "$WORK/x.png" >/dev/null 2>"$WORK/err"
rc=$?
[ $rc = 1 ] && grep -q "pipe.pfm: not a regular file (a FIFO: refused, it would block)" "$WORK/err" \
  && pass "c.image.load of a FIFO is refused at once" || fail "image FIFO" "exit $rc: $(cat "$WORK/err")"
# Readers check before they allocate (issue 31): a header that claims more than its file holds is
# refused at once, with both numbers.
printf 'PF\n32768 32768\n-1.0\n\x00\x00\x80\x3f' >"$WORK/huge.pfm"
expect_error "a 26-byte PFM claiming 32768^2" 1 "huge.pfm: a 32768x32768 image is out of range" - -- \
  "$CAUSTICA" compare "$WORK/huge.pfm" "$WORK/huge.pfm"
printf 'PF\n4000 4000\n-1.0\n\x00\x00\x80\x3f' >"$WORK/short.pfm"
expect_error "a PFM whose header claims more data than it holds" 1 \
  "short.pfm: truncated: its header says 4000x4000, which needs at least 192000000 bytes, the file has 4" - -- \
  "$CAUSTICA" compare "$WORK/short.pfm" "$WORK/short.pfm"
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 10000 +X 10000\n\x02\x02\x27\x10' >"$WORK/short.hdr"
expect_error "a 51-byte HDR claiming 10000^2" 1 "short.hdr: truncated: its header says 10000x10000" - -- \
  "$CAUSTICA" compare "$WORK/short.hdr" "$WORK/short.hdr"
"$CAUSTICA" convert tests/data/quadrants.png "$WORK/small.exr" >/dev/null 2>&1
python3 - "$WORK/small.exr" "$WORK/wide.exr" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
for name in (b"dataWindow\0box2i\0", b"displayWindow\0box2i\0"):
    at = data.index(name) + len(name) + 4           # past the attribute's size
    data[at:at + 16] = struct.pack("<4i", 0, 0, 8191, 16383)
open(sys.argv[2], "wb").write(bytes(data))
PY
# refused from its header, before 4 GB are allocated: in 700 MB of address space (no clock read)
space=700000
(ulimit -v $space; exec "$CAUSTICA" compare "$WORK/small.exr" "$WORK/small.exr") >/dev/null 2>&1 || space=unlimited
expect_error "a small EXR whose dataWindow claims 8192x16384 (in $space KB of address space)" 1 \
  "wide.exr: truncated: its header says 8192x16384" - -- \
  bash -c "ulimit -v $space; exec \"\$0\" compare \"\$1\" \"\$1\"" "$CAUSTICA" "$WORK/wide.exr"
if command -v ffmpeg >/dev/null; then
  ffmpeg -v error -y -f lavfi -i testsrc=size=512x512 -frames:v 1 "$WORK/t.jpg" 2>/dev/null
  head -c $(( $(stat -c %s "$WORK/t.jpg") / 2 )) "$WORK/t.jpg" >"$WORK/cut.jpg"
  cat >"$WORK/tex.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 2, 0.01}, target = {0, 0, 0} } }
scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 2 },
                     material = c.material.diffuse { color = c.texture(c.param("path", "")) } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {8, 8} }
EOF
  "$CAUSTICA" render "$WORK/tex.lua" --set path="$WORK/t.jpg" --allow-read "$WORK" -o "$WORK/x.png" >/dev/null 2>"$WORK/err" \
    && pass "a whole JPEG loads" || fail "whole JPEG" "$(cat "$WORK/err")"
  rm -f "$WORK/x.png"
  expect_error "a truncated JPEG is refused, not padded with grey" 1 "cut.jpg: the JPEG ends early or is damaged" "$WORK/x.png" -- \
    "$CAUSTICA" render "$WORK/tex.lua" --set path="$WORK/cut.jpg" --allow-read "$WORK" -o "$WORK/x.png"
  python3 - "$WORK/t.jpg" "$WORK/tall.jpg" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read()[:3000])
at = data.index(b"\xff\xc0")                        # SOF0: length, precision, height, width
data[at + 5:at + 9] = struct.pack(">HH", 4096, 16384)
open(sys.argv[2], "wb").write(bytes(data))
PY
  expect_error "a 3000-byte JPEG claiming 16384x4096" 1 "tall.jpg: truncated: its header says 16384x4096" "$WORK/x.png" -- \
    "$CAUSTICA" render "$WORK/tex.lua" --set path="$WORK/tall.jpg" --allow-read "$WORK" -o "$WORK/x.png"
fi
# Small ones (issue 31): integer options checked for overflow; a write past `ulimit -f` reported as
# the file's error (not SIGXFSZ), with the system's reason, for EXR as for PFM; the bench cache's
# numbers validated; a video named like an option stays a file name.
expect_error "--shard 0/99999999999 (an int overflow) is refused" 2 "--shard needs i/n" - -- \
  "$CAUSTICA" record scenes/demo.lua -o "$WORK/sh" --shard 0/99999999999
expect_error "--size 99999999999x2 is refused" 2 "--size needs WxH" - -- \
  "$CAUSTICA" render scenes/demo.lua --size 99999999999x2
for ext in pfm exr; do
  (ulimit -f 4; "$CAUSTICA" render scenes/demo.lua --size 128x128 -o "$WORK/big.$ext" >/dev/null 2>"$WORK/err"; echo $? >"$WORK/rc")
  [ "$(cat "$WORK/rc")" = 1 ] && grep -q "big.$ext: .*File too large" "$WORK/err" && [ "$(wc -l <"$WORK/err")" = 1 ] &&
    [ ! -e "$WORK/big.$ext" ] && ! ls "$WORK"/.big."$ext"* >/dev/null 2>&1 \
    && pass "past ulimit -f: one line naming big.$ext and 'File too large', nothing left" \
    || fail "ulimit -f ($ext)" "rc $(cat "$WORK/rc"): $(cat "$WORK/err")"
done
# Limits that hold against C-side work (issue 31): --script-timeout stops a backtracking pattern, a
# long gsub, a looping message handler and a looping __gc within a second of the limit (the
# watchdog: they run where the count hook cannot); --script-memory counts images' pixels.
limit_case() { # NAME LUA-LINES [EXPECTED-TEXT]
  printf 'local c = require "caustica"\n%s\nlocal g = c.graph()\ng:add("shade", c.pass.shade {})\ng:output("shade.color")\nreturn { scene = c.scene {}, graph = g, size = {8, 8} }\n' \
    "$2" >"$WORK/limit.lua"
  # the limit's own message is what shows that the limit stopped it (no clock is read here: timeout
  # 120 is a hang guard, its exit 124 a failure)
  timeout 120 "$CAUSTICA" render "$WORK/limit.lua" --script-timeout 1 -o "$WORK/limit.png" >/dev/null 2>"$WORK/err"
  local rc=$?
  [ $rc = 1 ] && grep -qF "${3:-ran past --script-timeout}" "$WORK/err" && [ "$(wc -l <"$WORK/err")" = 1 ] \
    && pass "--script-timeout 1 stops $1, with one line" || fail "$1" "exit $rc: $(cat "$WORK/err")"
  rm -f "$WORK/limit.png"
}
# Patterns run in the bounded matcher (src/lua/lua_pattern.c), which looks at the clock as it works:
# the script's own error with its line, not the watchdog, even under a pcall.
pattern_stop="limit.lua:2: script ran longer than 1 s (in a string pattern; raise --script-timeout, 0 = no limit)"
limit_case "a backtracking pattern" 'local r = ("a"):rep(40):find(("a?"):rep(40) .. ("a"):rep(40) .. "b")' "$pattern_stop"
limit_case "a gsub over 100 kB" 'local r = (("x"):rep(100000)):gsub("(.-)(.-)(.-)c", "")' "$pattern_stop"
limit_case "string.find(100 kB, '.-.-.-b')" 'local r = string.find(("a"):rep(1e5), ".-.-.-b")' "$pattern_stop"
limit_case "a backtracking gmatch inside pcall" 'while true do pcall(function() for _ in ("a"):rep(40):gmatch(("a?"):rep(40) .. ("a"):rep(40) .. "b") do end end) end' \
  "script ran longer than 1 s"
limit_case "image operations in a loop (checked inside the C loop)" 'local a, b = c.image.new(2048, 2048), c.image.new(2048, 2048); while true do c.image.difference(a, b) end' \
  "limit.lua:2: script ran longer than 1 s (in image.difference; raise --script-timeout, 0 = no limit)"
limit_case "a looping message handler" 'xpcall(function() error("x") end, function() while true do end end)'
limit_case "a looping __gc" 'setmetatable({}, { __gc = function() while true do end end })'
printf 'local c = require "caustica"\nlocal img = c.image.new(16384, 16384)\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/bigimage.lua"
expect_error "--script-memory 64 counts an image's pixels (16384^2 is refused before it is made)" 1 \
  "bigimage.lua:2: a 16384x16384 image needs 4096 MB, which would take the script past --script-memory 64 MB" - -- \
  "$CAUSTICA" render "$WORK/bigimage.lua" --script-memory 64 -o "$WORK/x.png"
printf 'local c = require "caustica"\nlocal keep = {}\nfor i = 1, 8 do keep[i] = c.image.new(1024, 1024) end\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/manyimages.lua"
expect_error "--script-memory 64: the fourth 16 MB image is one too many" 1 \
  "manyimages.lua:3: a 1024x1024 image needs 16 MB, which would take the script past --script-memory 64 MB" - -- \
  "$CAUSTICA" render "$WORK/manyimages.lua" --script-memory 64 -o "$WORK/x.png"
printf 'local c = require "caustica"\nlocal m = c.mesh.grid { size = 1, resolution = 2000 }\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/bigmesh.lua"
expect_error "--script-memory 64 counts a mesh's arrays" 1 "bigmesh.lua:2: mesh 'grid' (4004001 vertices) needs 244 MB" - -- \
  "$CAUSTICA" render "$WORK/bigmesh.lua" --script-memory 64 -o "$WORK/x.png"
# Textures count too: a 2048^2 PNG (16 MB of texels) is refused at 8 MB from its header, before it is
# decoded; textures kept in a table add up; dropped ones are given back.
printf 'local c = require "caustica"\nc.image.new(2048, 2048):save("%s")\nc.image.new(512, 512):save("%s")\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  "$WORK/tex2048.png" "$WORK/tex512.png" >"$WORK/maketex.lua"
"$CAUSTICA" render "$WORK/maketex.lua" --allow-write "$WORK" -o "$WORK/x.png" >/dev/null 2>&1
printf 'local c = require "caustica"\nlocal t = c.texture("%s")\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  "$WORK/tex2048.png" >"$WORK/bigtex.lua"
expect_error "--script-memory 8 counts a texture's texels, checked from its header" 1 \
  "bigtex.lua:2: $WORK/tex2048.png: image of 2048x2048 texels needs 16.00 MB, more than the" - -- \
  "$CAUSTICA" render "$WORK/bigtex.lua" --script-memory 8 --allow-read "$WORK" -o "$WORK/x.png"
printf 'local c = require "caustica"\nlocal keep = {}\nfor i = 1, 40 do keep[i] = c.texture("%s") end\nlocal g = c.graph()\ng:add("shade", c.pass.shade {})\ng:output("shade.color")\nreturn { scene = c.scene {}, graph = g, size = {8, 8} }\n' \
  "$WORK/tex512.png" >"$WORK/manytex.lua"
expect_error "--script-memory 8: 1 MB textures kept in a table add up" 1 \
  "tex512.png: image of 512x512 texels needs 1.00 MB, more than the" - -- \
  "$CAUSTICA" render "$WORK/manytex.lua" --script-memory 8 --allow-read "$WORK" -o "$WORK/x.png"
printf 'local c = require "caustica"\nlocal keep = {}\nfor i = 1, 60 do keep[i] = c.mesh.load(c.asset("khronos/BoxTextured/BoxTextured.glb")) end\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$WORK/meshtex.lua"
expect_error "--script-memory 8: a glTF's textures count with its mesh, checked before each is decoded" 1 \
  "BoxTextured.glb image 0 '': image of 256x256 texels needs 0.25 MB, more than the" - -- \
  "$CAUSTICA" render "$WORK/meshtex.lua" --script-memory 8 -o "$WORK/x.png"
sed 's/keep\[i\] = c.texture/keep[1] = c.texture/; s/ end$/ collectgarbage() end/' "$WORK/manytex.lua" >"$WORK/droptex.lua"
"$CAUSTICA" render "$WORK/droptex.lua" --script-memory 8 --allow-read "$WORK" -o "$WORK/x.png" >/dev/null 2>"$WORK/err" \
  && pass "--script-memory 8: forty 1 MB textures, each dropped, are given back" || fail "dropped textures" "$(cat "$WORK/err")"
finish
