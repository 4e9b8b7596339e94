# Every fenced code block in README.md and docs/*.md runs as written: a Lua
# scene script renders (saved beside the scenes, so its asset paths are the
# project's), a Lua test snippet passes under `caustica test`. A block whose
# fence line is preceded by <!-- not run: REASON --> is skipped (the shell
# lines that install and build, which `make demo` and CI run themselves).
source "$(dirname "$0")/lib.sh"
BLOCKS="$WORK/blocks"
mkdir -p "$BLOCKS"
made=()
cleanup_blocks() { rm -f "${made[@]}"; }
trap 'cleanup_blocks; rm -rf "$WORK"' EXIT
for doc in README.md docs/*.md docs/*/*.md; do
  awk -v dir="$BLOCKS" -v doc="$(sed "s,/,_,g; s,\.md$,," <<<"$doc")" '
    /^<!-- not run/ { skip = 1; next }
    /^```/ {
      if (inside) { inside = 0; close(file); next }
      lang = substr($0, 4); n++
      if (skip || (lang != "lua" && lang != "sh")) { skip = 0; ignore = 1; inside = 1; file = "/dev/null"; next }
      ignore = 0; inside = 1; file = sprintf("%s/%s.%d.%s", dir, doc, n, lang); line = NR; next
    }
    inside { print > file; next }
    { if ($0 !~ /^[[:space:]]*$/) skip = 0 }
  ' "$doc"
done
count=0
for block in "$BLOCKS"/*; do
  [ -e "$block" ] || continue
  count=$((count + 1))
  name=$(basename "$block")
  case "$block" in
    *.sh)
      fail "$name" "a shell block that is not marked <!-- not run: ... --> (the test does not run shell blocks)" ;;
    *.lua)
      if grep -q 'require "caustica.test"' "$block"; then
        dest="$ROOT/tests/lua/.docs_${name%.lua}_test.lua"
        cp "$block" "$dest"; made+=("$dest")
        "$CAUSTICA" test "$dest" >"$WORK/out" 2>&1 && pass "$name: the test snippet passes" \
          || fail "$name" "$(tail -3 "$WORK/out")"
      else
        dest="$ROOT/scenes/.docs_${name}"
        cp "$block" "$dest"; made+=("$dest")
        "$CAUSTICA" render "$dest" --size 32x32 -o "$WORK/$name.png" >"$WORK/out" 2>&1 \
          && pass "$name: the scene script renders" || fail "$name" "$(tail -3 "$WORK/out")"
      fi ;;
  esac
done
[ "$count" -gt 0 ] && pass "$count code blocks found" || fail "code blocks" "none found"
finish
