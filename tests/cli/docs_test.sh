# The pass reference in docs/LUA_API.md is `caustica help passes --markdown`
# (regenerate it with the command in the block's first line); `help` itself
# answers for every pass and refuses an unknown one.
source "$(dirname "$0")/lib.sh"
sed -n '/^<!-- BEGIN passes/,/^<!-- END passes -->/p' docs/LUA_API.md | sed '1d;$d' >"$WORK/docs.md"
"$CAUSTICA" help passes --markdown >"$WORK/help.md"
if diff -u "$WORK/docs.md" "$WORK/help.md" >"$WORK/diff"; then
  pass "docs/LUA_API.md's pass reference equals caustica help passes --markdown"
else
  fail "docs/LUA_API.md's pass reference is stale" "regenerate it: $(head -20 "$WORK/diff")"
fi
for p in $("$CAUSTICA" help passes | sed -n 's/^\([a-z_]*\): .*/\1/p'); do
  "$CAUSTICA" help "$p" >"$WORK/one" 2>&1 && grep -q "^$p: " "$WORK/one" && pass "help $p" || fail "help $p" "$(head -1 "$WORK/one")"
done
expect_error "help for an unknown pass" 1 "no pass named 'nosuch' (known passes: shadow_map" - -- "$CAUSTICA" help nosuch
finish
