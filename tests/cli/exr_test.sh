# OpenEXR output and input: linear float RGBA equal to the PFM, extra
# layers for pass outputs (--aov pass.output, as Mogwai's frame capture
# writes them), frame patterns, compare and convert reading EXR (a layer as
# file.exr:layer), and a broken file refused cleanly.
source "$(dirname "$0")/lib.sh"
SCENE=tests/scenes/fog.lua
SET="--set ball=true --set technique=beams --size 32x32"
"$CAUSTICA" render $SCENE $SET -o "$WORK/a.exr" --aov beams.inscatter --aov shade.color >/dev/null 2>"$WORK/err" \
  || fail "render to EXR" "$(cat "$WORK/err")"
"$CAUSTICA" render $SCENE $SET -o "$WORK/a.pfm" >/dev/null 2>&1
line=$("$CAUSTICA" compare "$WORK/a.exr" "$WORK/a.pfm" 2>&1)
rel=$(metric rel_rmse "$line")
awk "BEGIN { exit !($rel < 1e-5) }" && pass "the EXR holds the output (== PFM: $line)" || fail "EXR == PFM" "$line"
"$CAUSTICA" render $SCENE $SET --set output=inscatter -o "$WORK/inscatter.pfm" >/dev/null 2>&1
# (two runs of the additive beams may differ in the last bits: blending order)
line=$("$CAUSTICA" compare "$WORK/a.exr:beams.inscatter" "$WORK/inscatter.pfm" 2>&1)
rel=$(metric rel_rmse "$line")
awk "BEGIN { exit !($rel < 1e-5) }" && pass "--aov beams.inscatter is a layer holding that output ($line)" \
  || fail "AOV layer" "$line"
"$CAUSTICA" record tests/scenes/deform.lua --size 24x24 -o "$WORK/seq/f_##.exr" --frames 0-1 >/dev/null 2>&1
[ -s "$WORK/seq/f_00.exr" ] && [ -s "$WORK/seq/f_01.exr" ] && pass "record into an EXR pattern" \
  || fail "EXR pattern" "$(ls "$WORK/seq" 2>&1)"
"$CAUSTICA" convert "$WORK/a.exr" "$WORK/a.png" >/dev/null 2>&1 && "$CAUSTICA" compare "$WORK/a.png" "$WORK/a.png" >/dev/null \
  && pass "convert reads EXR" || fail "convert EXR" "failed"
expect_error "a layer the file lacks, and the layers it has" 1 "no layer 'nope' (channels nope.R, nope.G, nope.B) in the EXR; its layers: beams.inscatter" - -- \
  "$CAUSTICA" compare "$WORK/a.exr:nope" "$WORK/a.pfm"
expect_error "a layer asked of an EXR that has none" 1 "no layer 'nope' (channels nope.R, nope.G, nope.B) in the EXR; it has no layers, only the image itself" - -- \
  "$CAUSTICA" compare "$WORK/seq/f_00.exr:nope" "$WORK/a.pfm"
expect_error "an --aov no pass makes: the graph's images and the nearest" 1 "did you mean beams.inscatter?" "$WORK/typo.exr" -- \
  "$CAUSTICA" render $SCENE $SET -o "$WORK/typo.exr" --aov beams.inscater
grep -q "the graph's images: .*beams.inscatter" "$WORK/stderr" && pass "--aov's error lists the graph's images" \
  || fail "--aov choices" "$(cat "$WORK/stderr")"
expect_error "--aov without EXR" 2 "--aov: extra layers need an EXR output" "$WORK/b.png" -- \
  "$CAUSTICA" render $SCENE $SET -o "$WORK/b.png" --aov shade.color
"$CAUSTICA" render tests/scenes/ball_lens.lua --size 32x32 -o "$WORK/d.exr" --aov shade.depth >/dev/null 2>"$WORK/d.err"
if command -v exrheader >/dev/null; then
  exrheader "$WORK/d.exr" | grep -q "shade.depth.Z, 32-bit floating-point" && pass "a depth buffer is a Z layer (exrheader)" \
    || fail "depth layer" "$(exrheader "$WORK/d.exr" 2>&1 | head -12)"
fi
"$CAUSTICA" convert "$WORK/d.exr:shade.depth" "$WORK/depth.pfm" >/dev/null 2>&1 \
  && python3 - "$WORK/depth.pfm" <<'PY' && pass "the depth layer holds camera distances (floor nearer at the bottom)" || fail "depth values" "$(cat "$WORK/d.err")"
import struct, sys
data = open(sys.argv[1], "rb").read()
head, dims, scale, body = data.split(b"\n", 3)
w, h = map(int, dims.split())
v = struct.unpack("<%df" % (w * h * 3), body[: w * h * 12])
# PFM rows run bottom to top: the floor's bottom row is nearer than its top row (or the sky, +inf)
bottom, top = v[(w // 2) * 3], v[((h - 1) * w + w // 2) * 3]
sys.exit(0 if 0.5 < bottom < top else 1)
PY
# What a compositor reads (issue 30): Z is the distance along the view axis (+inf where nothing is
# drawn), the object id its own channel, and the header's chromaticities, camera and frame.
cat >"$WORK/z.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0, 3}, target = {0, 0, 0}, fov = 40 } }
scene:add(c.light.directional { direction = {0, 0, -1}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 1 }, rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2) })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32}, fps = 24 }
EOF
"$CAUSTICA" render "$WORK/z.lua" -o "$WORK/z.exr" --aov shade.depth --aov shade.normal --frame 0 >/dev/null 2>"$WORK/z.err" \
  || fail "the Z scene" "$(cat "$WORK/z.err")"
if command -v exrheader >/dev/null; then
  exrheader "$WORK/z.exr" >"$WORK/z.head" 2>&1
  grep -q "^chromaticities (type chromaticities)" "$WORK/z.head" && grep -q "red   (0.64 0.33)" "$WORK/z.head" &&
    grep -q "^worldToCamera (type m44f)" "$WORK/z.head" && grep -q "^worldToNDC (type m44f)" "$WORK/z.head" &&
    grep -q "^framesPerSecond (type rational): 24000/1000" "$WORK/z.head" &&
    grep -q '^caustica:frame (type int): 0' "$WORK/z.head" && grep -q '^caustica:scene (type string): ".*z.lua"' "$WORK/z.head" &&
    grep -q '^software (type string): "caustica ' "$WORK/z.head" && grep -q "^    objectId, 32-bit floating-point" "$WORK/z.head" &&
    ! grep -q "shade.normal.A" "$WORK/z.head" \
    && pass "exrheader: chromaticities, worldToCamera, worldToNDC, framesPerSecond, caustica's attributes, objectId" \
    || fail "EXR header" "$(cat "$WORK/z.head")"
fi
if command -v oiiotool >/dev/null; then
  oiiotool "$WORK/z.exr" --ch shade.depth.Z -o "$WORK/zz.exr" >/dev/null 2>&1
  stats=$(oiiotool --stats "$WORK/zz.exr" 2>&1)
  grep -qE "Stats Min: 3\.0000[0-9]+ " <<<"$stats" && grep -qE "Stats Max: 3\.0000[0-9]+ " <<<"$stats" &&
    [ "$(sed -n 's/.*Stats InfCount: \([0-9]*\).*/\1/p' <<<"$stats")" -gt 0 ] \
    && pass "oiiotool: Z is 3 on a plane 3 in front of the camera, +inf beside it" || fail "Z values" "$stats"
  oiiotool "$WORK/z.exr" --ch A -o "$WORK/alpha.exr" >/dev/null 2>&1
  inf=$(sed -n 's/.*Stats InfCount: \([0-9]*\).*/\1/p' <<<"$stats")
  avg=$(oiiotool --stats "$WORK/alpha.exr" 2>&1 | sed -n 's/.*Stats Avg: \([0-9.]*\).*/\1/p')
  awk -v a="$avg" -v inf="$inf" 'BEGIN { exit !(inf > 0 && (a - (1 - inf / 1024.0))^2 < 1e-10) }' \
    && pass "alpha is coverage: 0 exactly where Z is +inf (mean $avg)" || fail "coverage alpha" "mean $avg, $inf background pixels"
  oiiotool "$WORK/z.exr" --ch objectId -o "$WORK/id.exr" >/dev/null 2>&1
  grep -q "Stats Max: 1.000000" <<<"$(oiiotool --stats "$WORK/id.exr" 2>&1)" && pass "oiiotool: objectId is 1 on the first object" \
    || fail "objectId" "$(oiiotool --stats "$WORK/id.exr" 2>&1)"
  oiiotool --info -v "$WORK/z.exr" 2>&1 | grep -qi "worldtocamera" && pass "oiiotool --info -v reads the camera" \
    || fail "oiiotool --info" "$(oiiotool --info -v "$WORK/z.exr" 2>&1 | head -20)"
fi
# Glass is no longer invisible to a compositor (issue 56): every render EXR carries the first surface of
# every object, glass included (the refraction pass draws it after the G-buffer, which left it out):
# Z and objectId; --aov holdout is the image over nothing. tests/scenes/glass_ids.lua: a glass ball
# (object 2, front 2.5 from the eye) before a wall (object 1, 4 away), the environment past it.
if command -v oiiotool >/dev/null; then
  "$CAUSTICA" render tests/scenes/glass_ids.lua -o "$WORK/ids.exr" --aov holdout -q >/dev/null 2>"$WORK/ids.err" \
    || fail "the glass scene" "$(cat "$WORK/ids.err")"
  at() { oiiotool "$WORK/ids.exr" --ch "$1" --cut "1x1+$2" --printstats 2>&1 | sed -n 's/.*Stats Avg: *\([-0-9.e]*\).*/\1/p' | head -1; }
  inf_at() { oiiotool "$WORK/ids.exr" --ch "$1" --cut "1x1+$2" --printstats 2>&1 | sed -n 's/.*Stats InfCount: *\([0-9]*\).*/\1/p' | head -1; }
  [ "$(at objectId 24+24)" = 2.000000 ] && awk "BEGIN { exit !(($(at Z 24+24) - 2.5)^2 < 1e-4) }" \
    && pass "the glass ball's pixels: objectId 2 and Z 2.5, its front surface ($(at Z 24+24))" \
    || fail "glass in the EXR" "objectId $(at objectId 24+24), Z $(at Z 24+24)"
  [ "$(at objectId 8+24)" = 1.000000 ] && [ "$(at Z 8+24)" = 4.000000 ] && [ "$(at A 8+24)" = 1.000000 ] \
    && pass "the wall beside it: objectId 1, Z 4, alpha 1" || fail "wall in the EXR" "$(at objectId 8+24) $(at Z 8+24)"
  [ "$(at objectId 24+6)" = 0.000000 ] && [ "$(inf_at Z 24+6)" = 1 ] && [ "$(at A 24+6)" = 0.000000 ] \
    && pass "past the wall: objectId 0, Z +inf, alpha 0" || fail "background in the EXR" "$(at objectId 24+6) $(at A 24+6)"
  [ "$(at holdout.R 24+6)" = 0.000000 ] && [ "$(at holdout.A 24+6)" = 0.000000 ] &&
    [ "$(at holdout.R 24+24)" = "$(at R 24+24)" ] && [ "$(at holdout.A 24+24)" = 1.000000 ] &&
    awk "BEGIN { exit !($(at R 24+6) > 0) }" \
    && pass "--aov holdout: the environment left out (0 where alpha is 0), the objects as rendered" \
    || fail "holdout" "past the wall $(at holdout.R 24+6) (beauty $(at R 24+6)), on the glass $(at holdout.R 24+24)"
fi
# The reference writes EXR too: the image and its caustic part as a layer.
"$CAUSTICA" reference "$WORK/z.lua" -o "$WORK/ref.exr" --spp 1 --photons 1000 >/dev/null 2>"$WORK/r.err" &&
  "$CAUSTICA" convert "$WORK/ref.exr:caustic" "$WORK/caustic.pfm" >/dev/null 2>>"$WORK/r.err" \
  && pass "reference -o x.exr with its caustic layer" || fail "reference EXR" "$(cat "$WORK/r.err")"
head -c 300 "$WORK/a.exr" >"$WORK/broken.exr"
expect_error "a truncated EXR" 1 "broken.exr" - -- "$CAUSTICA" compare "$WORK/broken.exr" "$WORK/a.pfm"
# An equirectangular environment from an EXR: the sky converted from its .hdr renders the same.
"$CAUSTICA" convert scenes/assets/env/sky.hdr "$WORK/sky.exr" >/dev/null 2>&1
"$CAUSTICA" render tests/scenes/sky.lua --set look=ground -o "$WORK/hdr.pfm" >/dev/null 2>&1
"$CAUSTICA" render tests/scenes/sky.lua --set look=ground --set env="$WORK/sky.exr" --allow-read "$WORK" \
  -o "$WORK/exr.pfm" >/dev/null 2>"$WORK/env.err"
line=$("$CAUSTICA" compare "$WORK/exr.pfm" "$WORK/hdr.pfm" 2>&1)
rel=$(metric rel_rmse "$line")
awk "BEGIN { exit !($rel < 0.01) }" && pass "c.environment reads an equirectangular EXR ($line)" \
  || fail "EXR environment" "$line $(cat "$WORK/env.err")"
finish
