# Binding by name: no shader names a binding number and no list of slot
# numbers exists (units are given after link, gl/gl_program.c); C binds
# through the program by the shader's name, and every name it binds is one
# a shader declares (a typo would bind nothing, silently). The renderer's
# two reserved names are the only units C names by number.
source "$(dirname "$0")/lib.sh"
ROOT=${2:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$ROOT"
bare=$(grep -rnE "binding *=" shaders || true)
[ -z "$bare" ] && pass "no shader gives a binding number" || fail "binding numbers in shaders" "$bare"
[ ! -e src/graph/bindings.h ] && [ ! -e shaders/common/bindings.glsl ] && pass "no global slot list" \
  || fail "a global slot list is back" "$(ls src/graph/bindings.h shaders/common/bindings.glsl 2>/dev/null)"
raw=$(grep -rnE "gl\.(BindTextureUnit|BindImageTexture|BindBufferBase|BindBufferRange)\(" src --include=*.c \
      | grep -v "^src/gl/gl_program.c:" | grep -vE "RENDERER_(UNIT|BINDING)_" || true)
[ -z "$raw" ] && pass "C binds units only through a program's names (and the renderer's reserved two)" \
  || fail "C binds a unit by number" "$raw"
missing=""
names=$(grep -rhoE 'gl_program_bind_(texture|texture_at|image|storage|uniform_block)\([a-z_>-]+, "[A-Za-z_0-9]+"' src \
        | sed 's/.*"\(.*\)"/\1/' | sort -u)
for n in $names; do
  grep -rqE "\b(uniform|buffer)\b[^;{]* $n\b" shaders || missing="$missing $n"
done
count=$(echo "$names" | wc -w)
[ -z "$missing" ] && pass "all $count names C binds are declared by a shader" \
  || fail "C binds names no shader declares" "$missing"
finish
