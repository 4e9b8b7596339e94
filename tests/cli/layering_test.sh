# Dependencies point down only (docs/ARCHITECTURE.md): a file under src/X
# includes headers of its own layer or of a lower one, in the order
#   core -> gl -> io -> scene -> graph -> passes -> reference -> lua -> app
source "$(dirname "$0")/lib.sh"
layers="core gl io scene graph passes reference lua app"
rank() { local i=0; for l in $layers; do [ "$l" = "$1" ] && { echo $i; return; }; i=$((i + 1)); done; echo 99; }
bad=0
for f in $(find src -name '*.c' -o -name '*.h' -o -name '*.cpp' | sort); do
  layer=$(echo "$f" | cut -d/ -f2)
  mine=$(rank "$layer")
  while IFS= read -r inc; do
    dep=${inc%%/*}
    [ "$dep" = "$inc" ] && continue
    theirs=$(rank "$dep")
    [ "$theirs" = 99 ] && continue
    if [ "$theirs" -gt "$mine" ]; then
      echo "  $f ($layer) includes $inc ($dep, a higher layer)"
      bad=$((bad + 1))
    fi
  done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f")
done
[ $bad = 0 ] && pass "no file includes a header from a higher layer" || fail "layering" "$bad includes point up (listed above)"
finish
