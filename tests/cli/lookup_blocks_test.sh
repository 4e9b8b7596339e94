# The distance map and the impostors as building blocks (issue 54: each was
# a private helper of its readers, built once per reader): the graph adds
# one for a reader that names none, shares it among readers that want the
# same one, keeps those of other sizes or contents apart, adds none for a
# reader whose values leave it unread, takes the script's own in its place
# (the same image), reuses it while nothing it shows changes (a recursive
# set is made every frame), and refuses a map of the wrong content by name.
# Refraction's image of what lies behind the glass is the block
# `shade { specular = false }` (it drew the diffuse objects itself).
source "$(dirname "$0")/lib.sh"
S=tests/scenes/lookup_blocks.lua
count() { grep -cE "^[a-z_0-9]+ +$2 " "$WORK/$1.txt"; }
for c in default named impostors imp_named two sizes beams photons recursion layered; do
  "$CAUSTICA" render $S --set case=$c --timings -o "$WORK/$c.pfm" >"$WORK/$c.txt" 2>&1 \
    || fail "render case=$c" "$(cat "$WORK/$c.txt")"
done
"$CAUSTICA" render $S --set case=layered --set nearby=false --timings -o "$WORK/far.pfm" >"$WORK/far.txt" 2>&1
same() { "$CAUSTICA" compare "$WORK/$1.pfm" "$WORK/$2.pfm" | grep -q "rmse=0 "; }

# the distance map
[ "$(count default distance_map)" = 1 ] && grep -qE '^distance_map +distance_map +[0-9.]+ +24 ' "$WORK/default.txt" \
  && grep -qE '^glass +refraction +[0-9.]+ +3 ' "$WORK/default.txt" && [ "$(count default impostors)" = 0 ] \
  && pass "refraction's map is a block: 24 draws (two layers, six faces, two receivers) there, refraction's own 3" \
  || fail "the added map" "$(cat "$WORK/default.txt")"
[ "$(count named distance_map)" = 1 ] && grep -qE '^dm +distance_map ' "$WORK/named.txt" && same default named \
  && pass "the script's distance_map in its place: none added, the same image" || fail "a named map" "$(cat "$WORK/named.txt")"
[ "$(count two distance_map)" = 1 ] && pass "two refraction passes at one size: one map" || fail "two readers" "$(cat "$WORK/two.txt")"
[ "$(count sizes distance_map)" = 2 ] && pass "at two sizes: two maps" || fail "two sizes" "$(cat "$WORK/sizes.txt")"
[ "$(count beams distance_map)" = 2 ] && grep -q "^  distances around" "$WORK/beams.txt" \
  && grep -q "^  two layers of radiance and distance around" "$WORK/beams.txt" \
  && pass "beam_caustics' distances and refraction's radiance: two maps" || fail "two contents" "$(cat "$WORK/beams.txt")"
"$CAUSTICA" info $S >"$WORK/i.txt" 2>&1
grep -qE "^ 3  distance_map +distance_map +kept; on frame 1 reuses its map" "$WORK/i.txt" \
  && grep -q "in  distance_map <- distance_map.map" "$WORK/i.txt" \
  && pass "a still scene: the map reused on frame 1" || fail "map reuse" "$(cat "$WORK/i.txt")"
expect_error "a map of distances where refraction reads radiance" 1 \
  "pass 'glass' (refraction): its distance map ('dm.map') holds distances alone: the lookups need content = \"radiance\"" \
  "$WORK/w.png" -- "$CAUSTICA" render $S --set case=wrong -o "$WORK/w.png"

# what lies behind the glass (lookup "scene")
"$CAUSTICA" info $S --set case=beams >"$WORK/ib.txt" 2>&1
"$CAUSTICA" info $S --set case=impostors >"$WORK/s.txt" 2>&1
[ "$(count default shade)" = 1 ] && grep -q "in  behind       <- shade.color" "$WORK/i.txt" \
  && grep -q "in  behind_depth <- shade.depth" "$WORK/i.txt" \
  && pass "the script's shade { specular = false } with the same shadow map serves as refraction's behind" \
  || fail "behind shared" "$(cat "$WORK/default.txt" "$WORK/i.txt")"
[ "$(count beams shade)" = 2 ] && grep -q "in  behind       <- shade_2.color" "$WORK/ib.txt" \
  && grep -q "added by the graph for 'glass'" "$WORK/ib.txt" \
  && pass "a script's shade with caustics is not the behind image: the graph adds one" \
  || fail "behind apart" "$(cat "$WORK/beams.txt" "$WORK/ib.txt")"
[ "$(count impostors shade)" = 1 ] && ! grep -q "in  behind" "$WORK/s.txt" \
  && pass "lookup = \"impostors\" reads no behind image" || fail "no behind" "$(cat "$WORK/s.txt")"

# the impostors
[ "$(count impostors impostors)" = 1 ] && [ "$(count impostors distance_map)" = 0 ] \
  && grep -qE '^impostors +impostors +[0-9.]+ +2 ' "$WORK/impostors.txt" \
  && pass "lookup = \"impostors\": an impostors block (the floor and the box), no map" \
  || fail "impostors" "$(cat "$WORK/impostors.txt")"
[ "$(count imp_named impostors)" = 1 ] && grep -qE '^imp +impostors ' "$WORK/imp_named.txt" && same impostors imp_named \
  && pass "the script's impostors in their place: none added, the same image" || fail "named impostors" "$(cat "$WORK/imp_named.txt")"
[ "$(count photons impostors)" = 1 ] && grep -qE '^impostors +impostors ' "$WORK/photons.txt" \
  && pass "photon_caustics and refraction at one size and shadow map: one set of impostors" \
  || fail "photons and refraction" "$(cat "$WORK/photons.txt")"
grep -q "^  3 impostors of 256 x 256 texels, drawn again for each level of recursion" "$WORK/recursion.txt" \
  && pass "recursion: the glass's impostor too, drawn again" || fail "recursion" "$(cat "$WORK/recursion.txt")"
"$CAUSTICA" info $S --set case=recursion >"$WORK/r.txt" 2>&1
grep -qE "^ 3  impostors +impostors +kept; runs every frame" "$WORK/r.txt" \
  && grep -qE "^ 3  impostors +impostors +kept; on frame 1 reuses its impostors" "$WORK/s.txt" \
  && pass "a still scene: the impostors reused on frame 1, made every frame with recursion" \
  || fail "impostors reuse" "$(cat "$WORK/r.txt" "$WORK/s.txt")"
[ "$(count layered impostors)" = 1 ] && [ "$(count far impostors)" = 0 ] \
  && pass "layered_refraction: a set where nearby, none without" || fail "layered" "$(cat "$WORK/layered.txt" "$WORK/far.txt")"
finish
