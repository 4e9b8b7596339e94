# The C-GLSL contract by name (issue 54): every uniform, sampler, image and
# storage block a C file names as a string literal (gl_program_uniform,
# gl_program_bind_texture, _texture_at, _image, _storage) is declared in
# some shader under shaders/. A misspelt name is location -1 to GL, set in
# silence; two names C set were declared nowhere (a define spelt them).
source "$(dirname "$0")/lib.sh"
names() { grep -rhoE "$1\([a-z_>.-]+, \"[A-Za-z_0-9]+" src | sed -E 's/.*"//' | sort -u; }
missing=""
count=0
for n in $(names 'gl_program_uniform') $(names 'gl_program_bind_(texture|texture_at|image)'); do
  count=$((count + 1))
  grep -rqE "uniform[^;]*\\b$n\\b" shaders || missing="$missing $n"
done
for n in $(names 'gl_program_bind_storage'); do
  count=$((count + 1))
  grep -rqE "buffer +$n\\b" shaders || missing="$missing block:$n"
done
[ "$count" -gt 200 ] && [ -z "$missing" ] && pass "the $count names C gives shaders are declared in them" \
  || fail "names C gives shaders" "${missing:-only $count names found}"
finish
