# The C-GLSL contract by name (issue 54): every uniform, sampler, image and
# storage block a C file names as a string literal (gl_program_uniform,
# gl_program_bind_texture, _texture_at, _image, _storage) is declared in
# some shader under shaders/. A misspelt name is location -1 to GL, set in
# silence; two names C set were declared nowhere (a define spelt them).
source "$(dirname "$0")/lib.sh"
names() { grep -rhoE "$1\([a-z_>.-]+, \"[A-Za-z_0-9]+" src | sed -E 's/.*"//' | sort -u; }
# (gl_program_uniform_optional: what a shared helper sets where a program has it)
missing=""
count=0
for n in $(names 'gl_program_uniform(_optional)?') $(names 'gl_program_bind_(texture|texture_at|image)'); do
  count=$((count + 1))
  grep -rqE "uniform[^;]*\\b$n\\b" shaders || missing="$missing $n"
done
for n in $(names 'gl_program_bind_storage'); do
  count=$((count + 1))
  grep -rqE "buffer +$n\\b" shaders || missing="$missing block:$n"
done
[ "$count" -gt 200 ] && [ -z "$missing" ] && pass "the $count names C gives shaders are declared in them" \
  || fail "names C gives shaders" "${missing:-only $count names found}"

# ... and at run time: a name C asks a program for that none of its stages
# declares is an error naming the pass and the name, not location -1 in
# silence (a script's misspelt uniform here: `gian` for `gain`)
expect_error "a misspelt uniform" 1 \
  "pass 'invert' (fullscreen): its shaders do not declare 'gian' (" "$WORK/out.png" -- \
  "$CAUSTICA" render tests/scenes/passes.lua --set mode=misspelt_uniform -o "$WORK/out.png"
"$CAUSTICA" render tests/scenes/passes.lua --set mode=fullscreen -o "$WORK/ok.png" -q >/dev/null 2>&1 \
  && pass "the same pass with the name spelt right renders" || fail "the right spelling" "exit $?"
finish
