# The distance map as a building block (issue 54: it was refraction's and
# beam_caustics' private helper, one per reader): the graph adds it for a
# reader that names none, shares it among readers that want the same map,
# keeps maps of other sizes or contents apart, adds none for a lookup that
# reads none, takes the script's own in its place (the same image), reuses
# it while nothing it shows changes, and refuses a map of the wrong content
# by name.
source "$(dirname "$0")/lib.sh"
S=tests/scenes/distance_map_block.lua
maps() { grep -cE '^[a-z_0-9]+ +distance_map ' "$WORK/$1.txt"; }
for c in default named impostors two sizes beams; do
  "$CAUSTICA" render $S --set case=$c --timings -o "$WORK/$c.pfm" >"$WORK/$c.txt" 2>&1 \
    || fail "render case=$c" "$(cat "$WORK/$c.txt")"
done
[ "$(maps default)" = 1 ] && grep -qE '^distance_map +distance_map +[0-9.]+ +24 ' "$WORK/default.txt" \
  && grep -qE '^glass +refraction +[0-9.]+ +5 ' "$WORK/default.txt" \
  && pass "refraction's map is a block: 24 draws (two layers, six faces, two receivers) there, refraction's own 5" \
  || fail "the added map" "$(cat "$WORK/default.txt")"
out=$("$CAUSTICA" compare "$WORK/default.pfm" "$WORK/named.pfm")
[ "$(maps named)" = 1 ] && grep -qE '^dm +distance_map ' "$WORK/named.txt" && grep -q "rmse=0 " <<<"$out" \
  && pass "the script's distance_map in its place: none added, the same image" || fail "a named map" "$out $(cat "$WORK/named.txt")"
[ "$(maps impostors)" = 0 ] && pass "lookup = \"impostors\": no map added" || fail "impostors" "$(cat "$WORK/impostors.txt")"
[ "$(maps two)" = 1 ] && pass "two refraction passes at one size: one map" || fail "two readers" "$(cat "$WORK/two.txt")"
[ "$(maps sizes)" = 2 ] && pass "at two sizes: two maps" || fail "two sizes" "$(cat "$WORK/sizes.txt")"
[ "$(maps beams)" = 2 ] && grep -q "^  distances around" "$WORK/beams.txt" \
  && grep -q "^  two layers of radiance and distance around" "$WORK/beams.txt" \
  && pass "beam_caustics' distances and refraction's radiance: two maps" || fail "two contents" "$(cat "$WORK/beams.txt")"
"$CAUSTICA" info $S >"$WORK/i.txt" 2>&1
grep -qE "^ 3  distance_map +distance_map +kept; on frame 1 reuses its map" "$WORK/i.txt" \
  && grep -q "in  distance_map <- distance_map.map" "$WORK/i.txt" \
  && pass "a still scene: the map reused on frame 1" || fail "reuse" "$(cat "$WORK/i.txt")"
expect_error "a map of distances where refraction reads radiance" 1 \
  "pass 'glass' (refraction): its distance map ('dm.map') holds distances alone: the lookups need content = \"radiance\"" \
  "$WORK/w.png" -- "$CAUSTICA" render $S --set case=wrong -o "$WORK/w.png"
finish
