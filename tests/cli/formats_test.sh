# Output formats people use (issue 56): -o x.jpg (web pages) and x.tif (review tools) carry the same
# tone-mapped sRGB bytes as x.png; a render's PNG is RGB (it was RGBA with alpha 255 everywhere);
# --half writes an EXR's beauty channels as half floats (what
# compositors expect) and leaves depth and the layers 32-bit. Checked with OpenImageIO's and
# OpenEXR's own tools where they are installed.
source "$(dirname "$0")/lib.sh"
S="scenes/glass_sphere.lua --size 96x96"
# shellcheck disable=SC2086
for ext in png jpg jpeg tif tiff; do
  "$CAUSTICA" render $S -o "$WORK/a.$ext" -q 2>"$WORK/err" || fail "render -o a.$ext" "$(cat "$WORK/err")"
done
line=$("$CAUSTICA" compare "$WORK/a.tif" "$WORK/a.png" 2>&1)
[ "$(metric rmse "$line")" = 0 ] && pass "a TIFF holds the PNG's pixels exactly ($line)" || fail "TIFF == PNG" "$line"
line=$("$CAUSTICA" compare "$WORK/a.jpg" "$WORK/a.png" 2>&1)
awk "BEGIN { exit !($(metric psnr "$line") > 32) }" && pass "a JPEG is the PNG within its compression ($line)" \
  || fail "JPEG ~ PNG" "$line"
cmp -s "$WORK/a.jpg" "$WORK/a.jpeg" && cmp -s "$WORK/a.tif" "$WORK/a.tiff" && pass ".jpeg and .tiff are the same formats" \
  || fail ".jpeg/.tiff" "differ"
"$CAUSTICA" record tests/scenes/deform.lua --size 24x24 -o "$WORK/seq/f_##.jpg" --frames 0-1 -q >/dev/null 2>&1
[ -s "$WORK/seq/f_00.jpg" ] && [ -s "$WORK/seq/f_01.jpg" ] && pass "record into a JPEG pattern" || fail "JPEG pattern" "$(ls "$WORK/seq" 2>&1)"
"$CAUSTICA" convert "$WORK/a.png" "$WORK/c.tif" --tonemap aces >/dev/null 2>&1 && [ -s "$WORK/c.tif" ] \
  && pass "convert --tonemap writes a TIFF" || fail "convert to TIFF" "missing"
expect_error "an unknown output format names the ones there are" 2 ".png, .jpg, .tif, .pfm, .hdr or .exr" - -- \
  "$CAUSTICA" render $S -o "$WORK/a.bmp"
expect_error "--half is for EXR" 2 "--half: half floats are for an EXR output" "$WORK/h.png" -- \
  "$CAUSTICA" render $S -o "$WORK/h.png" --half
# shellcheck disable=SC2086
"$CAUSTICA" render $S -o "$WORK/f.exr" -q && "$CAUSTICA" render $S -o "$WORK/h.exr" --half --aov shade.depth -q
line=$("$CAUSTICA" compare "$WORK/h.exr" "$WORK/f.exr" 2>&1)
awk "BEGIN { exit !($(metric rel_rmse "$line") < 1e-3 && $(metric rel_rmse "$line") > 0) }" \
  && pass "--half: the beauty within half precision of the float EXR ($line)" || fail "--half values" "$line"
if command -v exrheader >/dev/null; then
  exrheader "$WORK/h.exr" >"$WORK/hdr.txt"
  grep -q "^    R, 16-bit floating-point" "$WORK/hdr.txt" && grep -q "^    A, 16-bit floating-point" "$WORK/hdr.txt" &&
    grep -q "^    shade.depth.Z, 32-bit floating-point" "$WORK/hdr.txt" \
    && pass "--half: R, G, B, A are half floats, the depth layer 32-bit (exrheader)" || fail "--half channels" "$(cat "$WORK/hdr.txt")"
  exrheader "$WORK/f.exr" | grep -q "^    R, 32-bit floating-point" && pass "without --half the EXR stays 32-bit" \
    || fail "float EXR" "$(exrheader "$WORK/f.exr")"
fi
if command -v oiiotool >/dev/null; then
  for f in a.png a.jpg a.tif; do
    oiiotool --info "$WORK/$f" 2>&1 | grep -q "96 x   96, 3 channel, uint8" \
      && pass "$f: 8-bit RGB, no alpha channel (oiiotool)" || fail "$f channels" "$(oiiotool --info "$WORK/$f" 2>&1)"
  done
fi
finish
