# Every shipped scene still renders after a user copies it, alone, to an empty folder to edit it
# (issue 56): a scene names the project's assets with c.asset, never by a path relative to the
# tree. Each renders its first frame at 32x32 from the copy's folder.
source "$(dirname "$0")/lib.sh"
mkdir -p "$WORK/mine"
for scene in scenes/*.lua scenes/compare/*.lua; do
  name=$(basename "$scene")
  rm -rf "$WORK/mine"/*
  cp "$scene" "$WORK/mine/$name"
  (cd "$WORK/mine" && timeout 300 "$CAUSTICA" render "$name" --size 32x32 -o out.png -q) >/dev/null 2>"$WORK/err"
  rc=$?
  if [ $rc = 0 ] && [ -s "$WORK/mine/out.png" ]; then
    pass "$scene renders from a copy in an empty folder"
  else
    fail "$scene copied out of the tree" "exit $rc: $(head -2 "$WORK/err")"
  fi
done
finish
