# `caustica bench --sweep technique=all` and `caustica choose` on a small
# comparison scene: one frontier per technique, the table of best errors
# within 33 ms / 100 ms / 1 s, and choose reading the sweep from the bench
# cache (here a cached sweep whose numbers the test wrote, so the expected
# choice is known exactly).
source "$(dirname "$0")/lib.sh"
B="$WORK/bench"
OPTS=(--size 32x32 --frames 1 --error-frames 2 --ref-photons 3000 --ref-spp 8 -o "$B")
# choose without a cached sweep runs it (bench --sweep technique=all)
"$CAUSTICA" choose scenes/compare/fog.lua --error 10 "${OPTS[@]}" >"$WORK/out.txt" 2>"$WORK/err.txt" \
  && grep -q "running \`caustica bench" "$WORK/err.txt" && pass "choose runs the sweep when the cache has none" \
  || fail "choose without a cache" "$(tail -5 "$WORK/err.txt")"
for f in results.csv results.md frontier.md plot.svg flicker.svg; do
  [ -s "$B/$f" ] && pass "wrote $f" || fail "wrote $f" "missing"
done
rows=$(grep -c '^gpu,' "$B/results.csv")
[ "$rows" = 8 ] && [ "$(grep -c '^gpu,plain,' "$B/results.csv")" = 3 ] && [ "$(grep -c '^gpu,beams,' "$B/results.csv")" = 5 ] \
  && pass "every declared technique at its defaults and its settings (3 + 5)" || fail "rows" "$(cat "$B/results.csv")"
# an animated scene: the error is the mean over frames spread across it; a subset of its techniques
"$CAUSTICA" bench scenes/compare/ball.lua --sweep technique=plain,photons --size 32x32 --frames 1 --error-frames 3 \
  --ref-photons 3000 --ref-spp 8 -o "$WORK/ball" >"$WORK/ball.txt" 2>&1
grep -q "^errors: the mean over frames 0, 30, 59 of 60" "$WORK/ball.txt" && grep -q "means over frames 0, 30, 59" "$WORK/ball/results.md" \
  && [ "$(grep -c 'rendering the ground truth of frame' "$WORK/ball.txt")" = 6 ] \
  && pass "errors over 3 frames spread across the animation, one truth each and one of the frame after it (the flicker's), not one per technique" \
  || fail "error frames" "$(head -5 "$WORK/ball.txt")"
[ "$(grep -c '^gpu,' "$WORK/ball/results.csv")" = 8 ] && ! grep -q '^gpu,illumination' "$WORK/ball/results.csv" \
  && pass "--sweep technique=plain,photons: those two only (the photons at 7 settings)" || fail "technique subset" "$(cut -d, -f1-3 "$WORK/ball/results.csv")"
# issue 32: the flicker of every GPU row (the change from each error frame to
# the next against the truth's), a truth for each of those frames too, none
# for the reference's rows, and its plot
fcol=$(head -1 "$WORK/ball/results.csv" | tr ',' '\n' | grep -nx flicker | cut -d: -f1)
[ -n "$fcol" ] && [ "$(awk -F, -v c="$fcol" '$1 == "gpu" && $c + 0 > 0' "$WORK/ball/results.csv" | wc -l)" = 8 ] \
  && [ "$(awk -F, -v c="$fcol" '$1 == "reference" && $c != ""' "$WORK/ball/results.csv" | wc -l)" = 0 ] \
  && grep -q "rendering the ground truth of frame 31 " "$WORK/ball.txt" \
  && grep -q "^Flicker: the error of each error frame's change" "$WORK/ball/results.md" \
  && grep -q "flicker (error of the frame-to-frame change)" "$WORK/ball/flicker.svg" \
  && pass "flicker measured for every GPU row of the turning ball, and plotted" \
  || fail "flicker column" "$(cut -d, -f1-3,"${fcol:-1}" "$WORK/ball/results.csv"; grep -c 'rendering the ground truth' "$WORK/ball.txt")"
grep -q "^| plain |" "$B/frontier.md" && grep -q "^| beams |" "$B/frontier.md" && grep -q "^| reference (CPU) |" "$B/frontier.md" \
  && grep -q "≤ 33 ms | ≤ 100 ms | ≤ 1 s" "$B/frontier.md" && pass "the frontier table: each technique and the reference" \
  || fail "frontier table" "$(cat "$B/frontier.md")"
# the plot: one frontier line per technique and the reference's curve
[ "$(grep -c '<polyline' "$B/plot.svg")" = 3 ] && grep -q ">beams</text>" "$B/plot.svg" \
  && pass "one frontier per technique in the plot" || fail "plot" "$(grep -c '<polyline' "$B/plot.svg") lines"
cache=$(ls "$B"/cache/sweep_*.csv 2>/dev/null | head -1)
[ -n "$cache" ] && pass "the sweep is cached ($(basename "$cache"))" || fail "sweep cache" "none in $B/cache"

# A cached sweep with known numbers: choose must read it, not run anything.
head -1 "$cache" >"$WORK/header"
cols=$(head -1 "$cache" | tr ',' '\n' | wc -l)
err_col=$(head -1 "$cache" | tr ',' '\n' | grep -nx error | cut -d: -f1)
fl_col=$(head -1 "$cache" | tr ',' '\n' | grep -nx flicker | cut -d: -f1)
row() { # kind technique settings ms error [flicker] (in their columns; renderer and cpus left empty)
  local line="$1,$2,$3,$4,1"
  for ((i = 6; i <= cols; i++)); do
    if [ "$i" = "$err_col" ]; then line="$line,$5"; elif [ "$i" = "$fl_col" ]; then line="$line,${6:-}"; else line="$line,"; fi
  done
  echo "$line"
}
{
  cat "$WORK/header"
  row gpu plain defaults 5 0.9 0.01
  row gpu plain fog.steps=16 3 0.95
  row gpu beams defaults 40 0.20 0.10
  row gpu beams caustics.refine=0 20 0.30 0.2
  row gpu beams caustics.refine=2 80 0.12 0.04
  row reference "" "8 it" 1 0.01
} >"$cache"
cp "$cache" "$WORK/good.csv"
sed -i '2s/^gpu,plain,defaults,5,/gpu,plain,defaults,abc,/' "$cache"
"$CAUSTICA" choose scenes/compare/fog.lua --error 0.25 "${OPTS[@]}" --cached >/dev/null 2>"$WORK/bad.txt"
[ $? = 1 ] && grep -q ":2: frame_ms 'abc' and error '0.9' must be finite numbers >= 0" "$WORK/bad.txt" \
  && pass "a cache row whose time is not a number is refused with its line" || fail "cache numbers" "$(cat "$WORK/bad.txt")"
cp "$WORK/good.csv" "$cache"
"$CAUSTICA" choose scenes/compare/fog.lua --error 0.25 "${OPTS[@]}" >"$WORK/c1.txt" 2>"$WORK/c1e.txt"
grep -q "from the bench cache" "$WORK/c1e.txt" && ! grep -q "rendering" "$WORK/c1e.txt" \
  && pass "choose reads the cached sweep" || fail "cache read" "$(cat "$WORK/c1e.txt")"
grep -q "^scenes/compare/fog.lua: beams (defaults): 40.0 ms a frame" "$WORK/c1.txt" \
  && pass "--error 0.25: the cheapest within it (beams at its defaults, not refine=2)" || fail "--error" "$(cat "$WORK/c1.txt")"
grep -q 'g:add("caustics", c.pass.beam_caustics { light = LIGHT1 })' "$WORK/c1.txt" \
  && grep -q 'g:add("fog", c.pass.volume_light {.*add = { "caustics.inscatter" }' "$WORK/c1.txt" \
  && grep -q -- "--set technique=beams" "$WORK/c1.txt" && pass "the graph lines to paste, and the --set" \
  || fail "graph lines" "$(cat "$WORK/c1.txt")"
# --flicker bounds the flicker as --error the error: the cheapest within both
"$CAUSTICA" choose scenes/compare/fog.lua --error 0.25 --flicker 0.05 "${OPTS[@]}" >"$WORK/cf.txt" 2>"$WORK/cfe.txt"
grep -q "^scenes/compare/fog.lua: beams (caustics.refine=2): 80.0 ms a frame, .* 0.12, flicker 0.04$" "$WORK/cf.txt" \
  && pass "--error 0.25 --flicker 0.05: the cheapest within both (refine=2, not the defaults' flicker 0.1)" \
  || fail "--flicker" "$(cat "$WORK/cf.txt" "$WORK/cfe.txt")"
"$CAUSTICA" choose scenes/compare/fog.lua --flicker 0.05 "${OPTS[@]}" >"$WORK/cf2.txt" 2>&1
grep -q "beams (caustics.refine=2)" "$WORK/cf2.txt" && pass "--flicker alone: the most accurate within it" \
  || fail "--flicker alone" "$(cat "$WORK/cf2.txt")"
"$CAUSTICA" choose scenes/compare/fog.lua --flicker 0.005 "${OPTS[@]}" >/dev/null 2>"$WORK/cf3.txt"
[ $? = 1 ] && grep -q "reaches flicker 0.005 on this machine; .* the steadiest plain (defaults): flicker 0.01" "$WORK/cf3.txt" \
  && pass "no row within the flicker (fog.steps=16 has none measured): says so, with the steadiest" \
  || fail "flicker nothing fits" "$(cat "$WORK/cf3.txt")"
expect_error "--flicker needs a number" 2 "--flicker needs a relative flicker > 0" - -- \
  "$CAUSTICA" choose scenes/compare/fog.lua --flicker zero
"$CAUSTICA" choose scenes/compare/fog.lua --error 0.2 --time 30 "${OPTS[@]}" >"$WORK/c2.txt" 2>"$WORK/c2e.txt"
[ $? = 1 ] && grep -q "no technique of scenes/compare/fog.lua reaches error 0.2 within 30 ms" "$WORK/c2e.txt" \
  && pass "nothing fits: says so, with the nearest choices" || fail "nothing fits" "$(cat "$WORK/c2e.txt")"
"$CAUSTICA" choose scenes/compare/fog.lua --time 50 "${OPTS[@]}" >"$WORK/c3.txt" 2>&1
grep -q "beams (defaults)" "$WORK/c3.txt" && pass "--time 50: the most accurate within it" || fail "--time" "$(cat "$WORK/c3.txt")"
"$CAUSTICA" choose scenes/compare/fog.lua --error 0.15 --time 1000 "${OPTS[@]}" >"$WORK/c4.txt" 2>&1
grep -q "caustics.refine=2" "$WORK/c4.txt" && grep -q 'beam_caustics { light = LIGHT1, refine = 2 }' "$WORK/c4.txt" \
  && pass "a chosen setting appears in the graph line" || fail "setting in graph" "$(cat "$WORK/c4.txt")"

# The README's comparison scenes: choose, from the sweeps measured for the
# README (their CSVs kept in docs/bench/SCENE/cache), picks what the tables
# say: the most accurate within 1 s a frame is the best of frontier.md's
# "<= 1 s" column, the cheapest within an error the fastest row of
# results.csv that reaches it. Those sweeps were measured against truths of
# the spheres' triangles (before 2026-12-07): they are cached under
# --ref-tessellated's key, and read with it.
for scene in ball room; do
  table="docs/bench/$scene/frontier.md"
  # "| name | ... | 0.078 (settings, 206 ms) | ...": the 4th column's best
  want=$(awk -F'|' '/^\| / && $2 !~ /technique|reference|---/ {
           v = $5; gsub(/^ +| +$/, "", v); if (v == "—") next
           split(v, a, " "); e = a[1] + 0
           if (best == "" || e < best) { best = e; name = $2; gsub(/^ +| +$/, "", name)
             s = v; sub(/^[^(]*\(/, "", s); sub(/, [0-9.]+ ms\)$/, "", s); settings = s } }
         END { print name " (" settings ")" }' "$table")
  "$CAUSTICA" choose "scenes/compare/$scene.lua" --time 1000 --cached --ref-tessellated -o "docs/bench/$scene" >"$WORK/pick.txt" 2>"$WORK/pick.err"
  got=$(sed -n 1p "$WORK/pick.txt" | sed 's/^[^:]*: //; s/: [0-9.]* ms a frame.*//')
  [ -n "$want" ] && [ "$got" = "$want" ] && pass "$scene: --time 1000 picks the table's best within 1 s: $got" \
    || fail "$scene: choose against the table" "want '$want', got '$got' ($(head -2 "$WORK/pick.txt"))"
  csv="docs/bench/$scene/results.csv"
  # the cheapest row within the median error of the GPU rows
  limit=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "error") c = i; next } $1 == "gpu" { print $c }' "$csv" \
          | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
  want=$(awk -F, -v lim="$limit" 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "error") c = i; if ($i == "frame_ms") m = i }; next }
           $1 == "gpu" && $c <= lim && (best == "" || $m < best) { best = $m; w = $2 " (" $3 ")" } END { print w }' "$csv")
  "$CAUSTICA" choose "scenes/compare/$scene.lua" --error "$limit" --cached --ref-tessellated -o "docs/bench/$scene" >"$WORK/pick.txt" 2>"$WORK/pick.err"
  got=$(sed -n 1p "$WORK/pick.txt" | sed 's/^[^:]*: //; s/: [0-9.]* ms a frame.*//')
  [ -n "$want" ] && [ "$got" = "$want" ] && pass "$scene: --error $limit picks the cheapest row within it: $got" \
    || fail "$scene: choose --error" "want '$want', got '$got' ($(head -2 "$WORK/pick.txt"))"
done

expect_error "choose needs a bound" 2 "choose needs one scene script and --error E" - -- \
  "$CAUSTICA" choose scenes/compare/fog.lua
expect_error "no techniques table" 2 "returns no 'techniques' table" - -- \
  "$CAUSTICA" bench scenes/demo.lua --sweep technique=all --size 16x16 -o "$WORK/x"
expect_error "an unknown technique" 2 "declares no technique 'lasers' (it has: plain, beams, or all)" - -- \
  "$CAUSTICA" bench scenes/compare/fog.lua --sweep technique=lasers --size 16x16 -o "$WORK/x"
cat >"$WORK/bad.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, techniques = { { "a", sweep = { ["shade.x"] = 3 } } } }
LUA
expect_error "a malformed techniques table" 2 "techniques: a.sweep: each key a \"pass.param\" or scene parameter, each value a list" - -- \
  "$CAUSTICA" bench "$WORK/bad.lua" --sweep technique=all --size 16x16 -o "$WORK/x" --trusted
# A technique that leaves out part of the scene (its pass says so) is never
# chosen, whatever its numbers: illumination textures over water.
cat >"$WORK/pool.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 0}, target = {0, -1, 0}, up = {0, 0, -1}, fov = 40 },
                        background = {0, 0, 0} }
local sun = scene:add(c.light.directional { direction = {0.4, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0}, material = c.material.diffuse {} })
scene:add(c.water { size = 4, resolution = 17, depth = 1, fresnel = false })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
local tech = c.param("technique", "photons")
g:add("caustics", tech == "iwasaki" and c.pass.illumination_textures { light = sun } or c.pass.photon_caustics { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance", specular = false })
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32}, techniques = { metric = "caustic", { "photons" }, { "iwasaki" } } }
LUA
# passed_over NAME SCRIPT CHOSEN SKIPPED WHY OPTIONS...: bench SCRIPT's techniques, rewrite the cache so
# that SKIPPED is cheaper (5 ms) and more accurate (0.1) than CHOSEN (30 ms, 0.2), and expect choose to
# pass over SKIPPED saying WHY and to choose CHOSEN.
passed_over() {
  local name=$1 script=$2 chosen=$3 skipped=$4 why=$5 dir="$WORK/$1_bench"
  shift 5
  "$CAUSTICA" bench "$script" --sweep technique=all "$@" -o "$dir" >"$WORK/$name.bench.txt" 2>&1
  local cache
  cache=$(ls "$dir"/cache/sweep_*.csv 2>/dev/null | head -1)
  if [ -z "$cache" ]; then
    fail "bench of $name" "no sweep cache: $(tail -3 "$WORK/$name.bench.txt")"
    return
  fi
  head -1 "$cache" >"$WORK/$name.header"
  cols=$(head -1 "$cache" | tr ',' '\n' | wc -l)
  err_col=$(head -1 "$cache" | tr ',' '\n' | grep -nx error | cut -d: -f1)
  { cat "$WORK/$name.header"; row gpu "$chosen" defaults 30 0.2; row gpu "$skipped" defaults 5 0.1; } >"$cache"
  "$CAUSTICA" choose "$script" --error 0.5 "$@" -o "$dir" >"$WORK/$name.1.txt" 2>"$WORK/$name.1e.txt"
  grep -q "choose: $skipped is not considered: $why" "$WORK/$name.1e.txt" \
    && grep -q ": $chosen (defaults): 30.0 ms a frame" "$WORK/$name.1.txt" \
    && pass "$name: $skipped is not chosen, though cheaper and within the error" \
    || fail "$name" "$(cat "$WORK/$name.1.txt" "$WORK/$name.1e.txt")"
}
passed_over pool "$WORK/pool.lua" photons iwasaki "pass 'caustics' (illumination_textures) leaves out object 2 (water)" \
  --size 32x32 --frames 1 --error-frames 1 --ref-photons 3000 --ref-spp 8 --trusted
# Nor one whose caustics in fog are on surfaces only (issue 52): photons through a glass ball in a
# medium draw no shaft, so beams are chosen though photons are cheaper and within the error.
cat >"$WORK/fog.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {-3, 0.5, 0}, target = {0, 0.5, 0}, fov = 30 }, background = {0, 0, 0} }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene.medium = c.medium { sigma_s = {0.5, 0.4, 0.3}, sigma_a = {0.1, 0.2, 0.3}, box = {{-1, 0, -1}, {1, 1, 1}} }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, material = c.material.diffuse {} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, position = {0, 1.6, 0}, material = c.material.glass {} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
local tech = c.param("technique", "beams")
g:add("caustics", tech == "photons" and c.pass.photon_caustics { light = sun } or c.pass.beam_caustics { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance" })
g:add("fog", c.pass.volume_light { color = "shade.color", add = tech == "beams" and "caustics.inscatter" or nil })
g:output("fog.color")
return { scene = scene, graph = g, size = {32, 32}, techniques = { metric = "image", { "beams" }, { "photons" } } }
LUA
passed_over fog "$WORK/fog.lua" beams photons "pass 'caustics' (photon_caustics) makes caustics on surfaces only" \
  --size 16x16 --frames 1 --error-frames 1 --ref-photons 2000 --ref-spp 8 --trusted
finish
