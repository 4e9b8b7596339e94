# `make install` into a temporary prefix, then docs/TUTORIAL.md step by step
# from a folder outside the tree with the installed binary: each script block
# is written where its <!-- file: NAME --> says, each shell block runs in
# order, every command must succeed and every image it names must appear.
# The source tree is put out of reach (an empty tmpfs over it, in a private
# mount namespace) so that nothing can come from it; where this machine
# cannot make one, the test says so and still requires that the binary
# names the prefix as its data folder.
source "$(dirname "$0")/lib.sh"
BUILD=$(cd "$(dirname "$CAUSTICA")" && pwd)
PREFIX="$WORK/prefix"
unset CAUSTICA_ROOT CAUSTICA_ASSET_PATH

if cmake --install "$BUILD" --prefix "$PREFIX" >"$WORK/install.log" 2>&1 && [ -x "$PREFIX/bin/caustica" ] &&
   [ -d "$PREFIX/share/caustica/shaders/common" ] && [ -f "$PREFIX/share/caustica/lua/caustica/init.lua" ] &&
   [ -f "$PREFIX/share/caustica/scenes/assets/bunny_15k.glb" ]; then
  pass "make install puts the binary, shaders, Lua modules and assets under the prefix"
else
  fail "install" "$(tail -5 "$WORK/install.log")"
  finish; exit
fi

# The tutorial, as a script of its own: files written, commands run in order.
HOME_DIR="$WORK/somewhere/else"
mkdir -p "$HOME_DIR"
STEPS="$WORK/steps.sh"
# Lua blocks are rewritten step by step: keep each step's version beside the commands it precedes.
awk -v dir="$HOME_DIR" '
  /^<!-- file: / { file = $3; next }
  /^```lua/ && file { step++; out = sprintf("%s/.script.%02d.%s", dir, step, file); inside = "lua"; next }
  /^```sh/ { cmd++; out = sprintf("%s/.run.%02d.sh", dir, step); inside = "sh"; next }
  /^```/ && inside { close(out); inside = ""; file = ""; next }
  inside { print >> out; next }
' docs/TUTORIAL.md
{
  echo 'set -e'
  echo "export PATH=\"$PREFIX/bin:\$PATH\""
  echo "cd \"$HOME_DIR\""
  for s in "$HOME_DIR"/.script.*; do
    step=$(basename "$s" | cut -d. -f3)
    name=$(basename "$s" | cut -d. -f4-)
    echo "cp \"$s\" \"$HOME_DIR/$name\""
    if [ -f "$HOME_DIR/.run.$step.sh" ]; then
      while IFS= read -r line; do
        [ -n "$line" ] || continue
        printf 'echo "$ %s"\n%s\n' "${line//\"/\\\"}" "$line"
      done <"$HOME_DIR/.run.$step.sh"
    fi
  done
} >"$STEPS"
# The README's quick start first, as its reader would: the script saved as
# glass.lua, then its shell block's commands.
{
  echo "cd \"$HOME_DIR\""
  awk '/^## Quick start/ { q = 1 } q && /^```lua/ { inside = 1; next } inside && /^```/ { exit } inside' README.md \
    | sed 's/^/  /' | { echo "cat >glass.lua <<'LUA'"; sed 's/^  //'; echo "LUA"; }
  awk '/^## Quick start/ { q = 1 } q && /^```sh/ { inside = 1; next } inside && /^```/ { exit } inside' README.md \
    | sed 's/ *#.*$//' | while IFS= read -r line; do [ -n "$line" ] && printf 'echo "$ %s"\n%s\n' "$line" "$line"; done
} >"$WORK/quickstart.sh"
sed -i "3r $WORK/quickstart.sh" "$STEPS"
steps=$(ls "$HOME_DIR"/.script.* | wc -l)
[ "$steps" -ge 5 ] && pass "the tutorial has $steps steps" || fail "tutorial steps" "found $steps"

# The source tree out of reach: an empty tmpfs mounted over it.
hide="mount -t tmpfs none \"$ROOT\" && [ ! -e \"$ROOT/shaders\" ]"
if unshare -rm sh -c "$hide" 2>/dev/null; then
  RUN=(unshare -rm sh -c "$hide && exec bash \"$STEPS\"")
  hidden="with the source tree out of reach"
elif unshare -m sh -c "$hide" 2>/dev/null; then
  RUN=(unshare -m sh -c "$hide && exec bash \"$STEPS\"")
  hidden="with the source tree out of reach"
else
  RUN=(bash "$STEPS")
  hidden="(no mount namespace here: the source tree stays visible)"
  echo "note: unshare is not allowed on this machine; the tree is not hidden"
fi
if "${RUN[@]}" >"$WORK/tutorial.log" 2>&1; then
  pass "every step of docs/TUTORIAL.md runs from the installed prefix $hidden"
else
  fail "the tutorial from the installed prefix $hidden" "$(tail -8 "$WORK/tutorial.log")"
fi
for img in glass.png glass.pfm step1.png step2.png step3.png step4.png step5.png step8.png frames/frame_0012.png truth.pfm truth.png table.pfm; do
  [ -s "$HOME_DIR/$img" ] && pass "the tutorial made $img" || fail "the tutorial's $img" "missing"
done
grep -q "rel_rmse=" "$WORK/tutorial.log" && pass "compare printed the error against the truth" \
  || fail "compare against the truth" "$(grep -A2 compare "$WORK/tutorial.log" | head -3)"

# The installed binary's data folder is the prefix's, not the source tree's.
out=$(cd "$HOME_DIR" && "$PREFIX/bin/caustica" info table.lua --no-render --verbose 2>&1)
grep -q "$PREFIX/bin/../share/caustica" <<<"$out" && pass "the installed binary reads its data from the prefix" \
  || fail "the installed binary's data folder" "$(grep -i "data\|folder\|root" <<<"$out" | head -3)"

# c.asset: a folder of one's own in front of the project's, and a clear miss.
mkdir -p "$WORK/mine"
cp "$ROOT/scenes/assets/teapot.glb" "$WORK/mine/bunny_15k.glb"
printf 'local c = require "caustica"\nlocal m = c.mesh.load(c.asset "bunny_15k.glb")\nprint("triangles " .. m.triangle_count)\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' \
  >"$HOME_DIR/asset.lua"
a=$(cd "$HOME_DIR" && "$PREFIX/bin/caustica" info asset.lua --no-render 2>&1 | grep "^triangles")
b=$(cd "$HOME_DIR" && CAUSTICA_ASSET_PATH="$WORK/mine" "$PREFIX/bin/caustica" info asset.lua --no-render 2>&1 | grep "^triangles")
c=$(cd "$HOME_DIR" && "$PREFIX/bin/caustica" info asset.lua --no-render --asset-path "$WORK/mine" 2>&1 | grep "^triangles")
[ -n "$a" ] && [ -n "$b" ] && [ "$a" != "$b" ] && [ "$b" = "$c" ] \
  && pass "c.asset: --asset-path and CAUSTICA_ASSET_PATH come before the project's assets" \
  || fail "c.asset search order" "project '$a', env '$b', option '$c'"
printf 'local c = require "caustica"\nlocal m = c.mesh.load(c.asset "no_such.glb")\n' >"$HOME_DIR/missing.lua"
expect_error "c.asset names the folders it searched" 1 "missing.lua:2: c.asset 'no_such.glb': not found in the asset folders" - -- \
  "$PREFIX/bin/caustica" render "$HOME_DIR/missing.lua" -o "$WORK/x.png"
printf 'local c = require "caustica"\nlocal m = c.mesh.load(c.asset "../../../etc/passwd")\n' >"$HOME_DIR/escape.lua"
expect_error "c.asset refuses '..'" 1 "may not leave the asset folders" - -- \
  "$PREFIX/bin/caustica" render "$HOME_DIR/escape.lua" -o "$WORK/x.png"
finish
