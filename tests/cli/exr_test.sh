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
expect_error "a layer the file lacks" 1 "no layer 'nope'" - -- "$CAUSTICA" compare "$WORK/a.exr:nope" "$WORK/a.pfm"
expect_error "--aov without EXR" 2 "--aov: extra layers need an EXR output" "$WORK/b.png" -- \
  "$CAUSTICA" render $SCENE $SET -o "$WORK/b.png" --aov shade.color
"$CAUSTICA" render tests/scenes/ball_lens.lua --size 32x32 -o "$WORK/d.exr" --aov shade.depth >/dev/null 2>"$WORK/d.err"
if command -v exrheader >/dev/null; then
  exrheader "$WORK/d.exr" | grep -q "shade.depth.Z, 32-bit floating-point" && pass "a depth buffer is a Z layer (exrheader)" \
    || fail "depth layer" "$(exrheader "$WORK/d.exr" 2>&1 | head -12)"
fi
"$CAUSTICA" convert "$WORK/d.exr:shade.depth" "$WORK/depth.pfm" >/dev/null 2>&1 \
  && python3 - "$WORK/depth.pfm" <<'PY' && pass "the depth layer holds window depths (floor nearer at the bottom)" || fail "depth values" "$(cat "$WORK/d.err")"
import struct, sys
data = open(sys.argv[1], "rb").read()
head, dims, scale, body = data.split(b"\n", 3)
w, h = map(int, dims.split())
v = struct.unpack("<%df" % (w * h * 3), body[: w * h * 12])
# PFM rows run bottom to top: the floor's bottom row is nearer than its top row; both are in (0, 1)
bottom, top = v[(w // 2) * 3], v[((h - 1) * w + w // 2) * 3]
sys.exit(0 if 0 < bottom < top <= 1 else 1)
PY
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
