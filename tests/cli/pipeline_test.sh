# A farm's and a compositor's view (issue 30): one log line per frame off a
# terminal, `wrote` for render, --quiet; record's -o made as mkdir -p,
# `x.png` and `%04d` taken as frame patterns, the whole frame set checked
# before the first frame; the reference's worker threads follow the CPUs the
# process may use (taskset) or --threads, and it writes EXR.
source "$(dirname "$0")/lib.sh"
cat >"$WORK/anim.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local lamp = scene:add(c.light.point { position = {1, 2, 1}, intensity = {5, 5, 5} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0} })
local ball = scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {16, 16}, frames = 6,
         update = function(t) ball.position = {math.sin(t), 0, 0} end }
EOF

# One line per frame in a log (not a terminal: setsid, stdout and stderr to a file), on stdout.
setsid "$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/log_frames" >"$WORK/log" 2>&1 </dev/null
n=$(grep -cE '^frame [0-9]+ \([0-9]+/6\) [0-9.]+ s -> .*frame_000[0-5]\.png$' "$WORK/log")
[ "$n" = 6 ] && grep -q "^wrote 6 frames" "$WORK/log" && pass "record off a terminal: one line per frame, as written" \
  || fail "record's log" "$n frame lines: $(cat "$WORK/log")"
"$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/quiet_frames" --quiet >"$WORK/log" 2>&1
[ ! -s "$WORK/log" ] && [ -f "$WORK/quiet_frames/frame_0005.png" ] && pass "--quiet: no lines, the frames still written" \
  || fail "--quiet" "$(cat "$WORK/log")"
"$CAUSTICA" render "$WORK/anim.lua" -o "$WORK/one.png" >"$WORK/log" 2>&1
grep -qx "wrote $WORK/one.png" "$WORK/log" && pass "render says where it wrote" || fail "render's wrote line" "$(cat "$WORK/log")"

# bench says which variant it is on and how long is left.
"$CAUSTICA" bench "$WORK/anim.lua" --sweep shade.specular=true,false --frames 2 --ref-photons 5000 -o "$WORK/bench" \
  >/dev/null 2>"$WORK/err"
grep -q "^caustica: bench: variant 1/2$" "$WORK/err" && grep -qE "^caustica: bench: variant 2/2 \([0-9]+ s so far, about [0-9]+ s left\)$" "$WORK/err" \
  && pass "bench: variant i/N and the time left" || fail "bench progress" "$(cat "$WORK/err")"

# record -o: nested folders made; x.png and %04d are patterns.
"$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/n1/n2/f_####.png" --frames 0-1 >/dev/null 2>"$WORK/err" &&
  [ -f "$WORK/n1/n2/f_0001.png" ] && pass "record -o makes nested folders (mkdir -p)" || fail "nested -o" "$(cat "$WORK/err")"
"$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/r7/f.png" --frames 2 >/dev/null 2>"$WORK/err" &&
  [ -f "$WORK/r7/f_0000.png" ] && [ -f "$WORK/r7/f_0001.png" ] && [ ! -d "$WORK/r7/f.png" ] &&
  grep -q "names no frame number: writing $WORK/r7/f_####.png" "$WORK/err" \
  && pass "-o x.png without # is x_####.png, and says so" || fail "-o x.png" "$(ls "$WORK/r7" 2>&1) $(cat "$WORK/err")"
"$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/pct/shot_%04d.png" --frames 3-4 >/dev/null 2>"$WORK/err" &&
  [ -f "$WORK/pct/shot_0003.png" ] && [ -f "$WORK/pct/shot_0004.png" ] && pass "-o shot_%04d.png is a frame pattern" \
  || fail "%04d" "$(ls "$WORK/pct" 2>&1) $(cat "$WORK/err")"
expect_error "a frame set past the script's end is refused before any frame" 1 \
  "--frames: frame 6 is past the script's last frame 5" "$WORK/past" -- \
  "$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/past/f_####.png" --frames 4-7
[ ! -e "$WORK/past" ] && pass "and leaves no folder behind" || fail "refused set" "left $(ls -R "$WORK/past")"
"$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/longer" --frame-count 8 --quiet 2>"$WORK/err" &&
  [ "$(ls "$WORK/longer" | wc -l)" = 8 ] && pass "--frame-count 8 records eight frames of a six-frame script" \
  || fail "--frame-count" "$(ls "$WORK/longer" 2>&1) $(cat "$WORK/err")"
expect_error "--video with --shard is refused" 2 "--video with --shard would encode only this shard's frames" - -- \
  "$CAUSTICA" record "$WORK/anim.lua" -o "$WORK/v" --shard 0/2 --video "$WORK/v.mp4"

# The reference's threads: the CPUs this process may use, or --threads.
cpus=$(nproc)
"$CAUSTICA" reference "$WORK/anim.lua" -o "$WORK/ref.pfm" --spp 1 --photons 2000 >"$WORK/log" 2>&1
grep -q "on $cpus thread" "$WORK/log" && pass "the reference runs one worker per CPU it may use ($cpus)" \
  || fail "reference threads" "$(cat "$WORK/log")"
grep -qE "^reference: iteration 1/1, [0-9]+ photons, [0-9.]+ s$" "$WORK/log" && ! grep -q $'\r' "$WORK/log" \
  && pass "the reference's progress off a terminal: whole lines, no carriage returns" || fail "reference log" "$(cat -A "$WORK/log")"
if command -v taskset >/dev/null; then
  taskset -c 0 "$CAUSTICA" reference "$WORK/anim.lua" -o "$WORK/ref.pfm" --spp 1 --photons 2000 >"$WORK/log" 2>&1
  grep -q "on 1 thread," "$WORK/log" && pass "under taskset -c 0 it runs one worker thread" \
    || fail "reference under taskset" "$(cat "$WORK/log")"
fi
"$CAUSTICA" reference "$WORK/anim.lua" -o "$WORK/ref3.pfm" --spp 1 --photons 2000 --threads 3 >"$WORK/log" 2>&1
grep -q "on 3 threads" "$WORK/log" && cmp -s "$WORK/ref.pfm" "$WORK/ref3.pfm" \
  && pass "--threads 3: three workers, the same image as one (deterministic for a seed)" \
  || fail "--threads" "$(cat "$WORK/log"); same image: $(cmp "$WORK/ref.pfm" "$WORK/ref3.pfm" && echo yes)"
"$CAUSTICA" reference "$WORK/anim.lua" -o "$WORK/ref.exr" --spp 1 --photons 2000 >/dev/null 2>"$WORK/err" &&
  line=$("$CAUSTICA" compare "$WORK/ref.exr" "$WORK/ref.pfm") && [ "$(metric rmse "$line")" = 0 ] \
  && pass "reference -o x.exr writes the same linear image" || fail "reference EXR" "$(cat "$WORK/err") ${line:-}"
# compare: a mask from a PNG, and a robust metric one hot pixel cannot swamp.
python3 - "$WORK" <<'PY'
import struct, sys, zlib
w = h = 16
def pfm(path, hot):
    px = [0.2] * (w * h * 3)
    if hot:
        px[0:3] = [500.0, 500.0, 500.0]
    open(path, "wb").write(b"PF\n%d %d\n-1.0\n" % (w, h) + struct.pack("<%df" % len(px), *px))
pfm(sys.argv[1] + "/flat.pfm", False)
pfm(sys.argv[1] + "/hot.pfm", True)
# a PNG mask: white but for the first row (PFM's first row is the image's bottom row; PNG's top)
rows = b"".join(b"\0" + bytes([0 if y == h - 1 else 255] * w) for y in range(h))
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)) + \
      chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")
open(sys.argv[1] + "/mask.png", "wb").write(png)
PY
line=$("$CAUSTICA" compare "$WORK/hot.pfm" "$WORK/flat.pfm")
awk -v r="$(metric rel_rmse "$line")" -v l="$(metric log_rmse "$line")" 'BEGIN { exit !(r > 100 && l < 0.5) }' \
  && pass "compare's log_rmse stays small where one hot pixel makes rel_rmse $(metric rel_rmse "$line")" \
  || fail "log_rmse" "$line"
line=$("$CAUSTICA" compare "$WORK/hot.pfm" "$WORK/flat.pfm" --mask "$WORK/mask.png")
[ "$(metric rmse "$line")" = 0 ] && pass "compare --mask with a PNG leaves the hot row out" || fail "--mask PNG" "$line"
# bench records the renderer and CPUs that measured; choose says when the cache is another machine's.
cat >"$WORK/tech.lua" <<'EOF'
local c = require "caustica"
local technique = c.param("technique", "plain")
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0.3, -1, -0.2}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass {} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 256 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", specular = technique == "plain" })
if technique == "plain" then g:output("shade.color") else
  g:add("glass", c.pass.layered_refraction { color = "shade.color" })
  g:output("glass.color")
end
return { scene = scene, graph = g, size = {24, 24}, techniques = { metric = "image", { "plain" }, { "layered" } } }
EOF
"$CAUSTICA" choose "$WORK/tech.lua" --time 10000 --frames 1 --ref-photons 2000 --ref-spp 8 -o "$WORK/cb" >/dev/null 2>"$WORK/err"
csv=$(ls "$WORK"/cb/cache/sweep_*.csv 2>/dev/null | head -1)
here=$(sed -n '2p' "$csv" | awk -F, '{print $(NF-1)}')
[ -n "$csv" ] && head -1 "$csv" | grep -q ",renderer,cpus$" && [ -n "$here" ] && grep -q "^Measured on $here, [0-9]* CPU" "$WORK/cb/results.md" \
  && pass "bench records the renderer and CPUs in its cache and tables ($here)" || fail "bench's renderer" "$(head -2 "$csv" 2>&1)"
svg="$WORK/cb/plot.svg"
grep -q "hollow: dominated" "$svg" && ! grep -qE "[0-9]e[+-][0-9]+ ms" "$svg" \
  && pass "the plot: a legend for hollow points, no 1e+03 ms (guides: tests/unit/test_plot.c)" || fail "plot" "$(head -c 800 "$svg")"
[ -n "$csv" ] && sed -i "2,\$s/$here/NVIDIA H200 (a GPU node)/" "$csv"
"$CAUSTICA" choose "$WORK/tech.lua" --time 10000 --frames 1 --ref-photons 2000 --ref-spp 8 -o "$WORK/cb" --cached >/dev/null 2>"$WORK/err"
grep -q "warning: the cached sweep was measured on NVIDIA H200 (a GPU node), this machine renders with $here" "$WORK/err" \
  && pass "choose says when the cache was measured on another renderer" || fail "choose's renderer warning" "$(cat "$WORK/err")"
# --truth-spp sets the ground truth's iterations (else 16 x --ref-spp, 128 at the least: --ref-spp 8 alone
# could not shorten it), and refuses one shorter than the curve's longest reference.
"$CAUSTICA" choose "$WORK/tech.lua" --time 10000 --frames 1 --ref-photons 2000 --ref-spp 8 --truth-spp 16 -o "$WORK/cb16" \
  >/dev/null 2>"$WORK/err"
grep -q "rendering the ground truth of frame 0 (16 iterations of 2000 photons)" "$WORK/err" \
  && pass "--truth-spp 16: the truth runs 16 iterations" || fail "--truth-spp" "$(cat "$WORK/err")"
expect_error "--truth-spp below --ref-spp" 1 "--truth-spp 8 is below --ref-spp 16" - -- \
  "$CAUSTICA" bench "$WORK/tech.lua" --sweep technique=all --ref-spp 16 --truth-spp 8 -o "$WORK/cb8"
expect_error "--truth-spp out of range" 2 "--truth-spp needs a count from 8 to 1000000, got '4'" - -- \
  "$CAUSTICA" bench "$WORK/tech.lua" --sweep technique=all --truth-spp 4
# convert --tonemap: the same tone mapping as render -o x.png (the renderer's own present pass).
cat >"$WORK/aces.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} }, background = {0.3, 0.5, 0.9} }
scene:add(c.light.point { position = {0.5, 2, 1}, intensity = {30, 28, 25} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.diffuse { color = {0.9, 0.3, 0.2} } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32}, tonemap = "aces", exposure = 1.5 }
EOF
"$CAUSTICA" render "$WORK/aces.lua" -o "$WORK/aces.png" -q && "$CAUSTICA" render "$WORK/aces.lua" -o "$WORK/aces.pfm" -q &&
  "$CAUSTICA" convert "$WORK/aces.pfm" "$WORK/conv.png" --tonemap aces --exposure 1.5 &&
  line=$("$CAUSTICA" compare "$WORK/aces.png" "$WORK/conv.png") && [ "$(metric rmse "$line")" = 0 ] \
  && "$CAUSTICA" convert "$WORK/aces.pfm" "$WORK/plain.png" && line=$("$CAUSTICA" compare "$WORK/aces.png" "$WORK/plain.png") \
  && [ "$(metric rmse "$line")" != 0 ] \
  && pass "convert --tonemap aces --exposure 1.5 equals render's PNG (without it, a plain clamp differs)" \
  || fail "convert --tonemap" "${line:-}"
expect_error "convert --tonemap to a linear format" 2 "--tonemap: " - -- \
  "$CAUSTICA" convert "$WORK/aces.pfm" "$WORK/x.exr" --tonemap aces
finish
