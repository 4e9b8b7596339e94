# Inputs typed beyond "a texture" (issue 54): a pass's shadow input takes a
# shadow_map pass's depth and nothing else, said when the graph is checked
# (before, any texture there rendered unshadowed, exit 0, no word).
source "$(dirname "$0")/lib.sh"
S=tests/scenes/graph_checks.lua
for pass in shade refraction volume_light; do
  case=$([ $pass = shade ] && echo shadow || echo $pass)
  slot=$([ $pass = shade ] && echo "shadow\\[2\\]" || echo "shadow\\[1\\]")
  expect_error "$pass { shadow = a colour image }: refused when the graph is checked" 1 \
    "pass 'out' ($pass) reads" "$WORK/a_$pass.png" -- "$CAUSTICA" render $S --set case=$case --set second=first.color \
    -o "$WORK/a_$pass.png"
  grep -qE "reads $slot = 'first.color', a texture that is not a shadow_map's" "$WORK/stderr" \
    && pass "$pass: the message names the item and what is expected" || fail "$pass message" "$(cat "$WORK/stderr")"
  "$CAUSTICA" render $S --set case=$case -o "$WORK/b_$pass.png" \
    >"$WORK/b.txt" 2>&1 && pass "$pass: a shadow map's depth is taken" || fail "$pass with a shadow map" "$(cat "$WORK/b.txt")"
done
finish
