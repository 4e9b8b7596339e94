# src/graph/bindings.h and shaders/common/bindings.glsl name the same
# binding points with the same numbers, and no shader or C file binds by a
# bare number where a name exists.
source "$(dirname "$0")/lib.sh"
defs() { sed -n 's/^#define \([A-Z_0-9]*\) \([0-9]*\).*/\1 \2/p' "$1" | grep -v "^CAUSTICA_"; }
if diff <(defs src/graph/bindings.h) <(defs shaders/common/bindings.glsl) >"$WORK/diff"; then
  pass "bindings.h and bindings.glsl agree ($(defs src/graph/bindings.h | wc -l) names)"
else
  fail "bindings.h and bindings.glsl differ" "$(cat "$WORK/diff")"
fi
bare=$(grep -rnE "binding *= *[0-9]" shaders | grep -v "shaders/common/bindings.glsl" || true)
[ -z "$bare" ] && pass "no shader binds by a bare number" || fail "bare binding numbers in shaders" "$bare"
bare=$(grep -rnE "(BindTextureUnit|BindBufferBase)\((GL_[A-Z_]+, )?\(?(GLuint\))?\(?[0-9]" src --include=*.c || true)
[ -z "$bare" ] && pass "no C file binds a unit or buffer by a bare number" || fail "bare binding numbers in C" "$bare"
finish
