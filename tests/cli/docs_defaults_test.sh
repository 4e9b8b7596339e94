# No stale default in the docs: every `pass { param, param = value, ... }`
# signature in the README and docs/ (LUA_API's "As built", the technique
# pages), and every "`param` value" of
# the README's table of defaults, equals what `caustica help PASS` says the
# code's default is. (The pass reference itself is generated: docs_test.sh.)
source "$(dirname "$0")/lib.sh"
passes=" $("$CAUSTICA" help passes | sed -n 's/^\([a-z_]*\): .*/\1/p' | tr '\n' ' ') "

# default_of PASS PARAM: the default `help PASS` prints, quotes kept.
default_of() {
  "$CAUSTICA" help "$1" 2>/dev/null | awk -v p="$2" '$1 == p { for (i = 2; i < NF; i++) if ($i == "default") { print $(i + 1); exit } }'
}
same() { # same DOC_VALUE CODE_VALUE: numbers compared as numbers
  [ "$1" = "$2" ] && return 0
  awk -v a="$1" -v b="$2" 'BEGIN { exit !(a ~ /^-?[0-9.e+-]+$/ && b ~ /^-?[0-9.e+-]+$/ && a + 0 == b + 0) }'
}
checked=0
check() { # check WHERE PASS PARAM VALUE
  local code
  code=$(default_of "$2" "$3")
  [ -n "$code" ] || return 0 # a parameter with no single default (an input, a list)
  checked=$((checked + 1))
  same "$4" "$code" || fail "$1: $2's $3" "the docs say $4, the code's default is $code"
}

# `pass { name, name = value, ... }` or `c.pass.pass { ... }` signatures anywhere in the docs but the
# generated pass reference (enum lists: the first choice).
while read -r span; do
    pass=${span#\`}; pass=${pass#c.pass.}; pass=${pass%% *}
    [[ $passes == *" $pass "* ]] || continue
    # a signature (some parameters named without a value), not an example such as `shade { specular = false }`
    grep -qE '[{,] *[a-z_]+ *[,}]' <<<"$span" || continue
    while read -r item; do
      check "the docs" "$pass" "${item%% =*}" "${item#*= }"
    done < <(grep -oE '[a-z_]+ = ("[^"]*"|-?[0-9][0-9.e+-]*|true|false)' <<<"$span")
    echo "$pass" >>"$WORK/lua_api_passes"
done < <(cat README.md docs/*.md docs/techniques/*.md | sed '/^<!-- BEGIN passes/,/^<!-- END passes/d' | tr '\n' ' ' | grep -oE '`(c\.pass\.)?[a-z_]+ \{[^`}]*\}')
# README: the table under "How the defaults were chosen".
while IFS='|' read -r _ col_pass col_defaults _; do
  pass=$(grep -oE '`[a-z_]+`' <<<"$col_pass" | head -1 | tr -d '`')
  while read -r item; do
    name=${item%%\` *}; name=${name#\`}
    check "README.md" "$pass" "$name" "${item#*\` }"
  done < <(grep -oE '`[a-z_]+` ("[^"]*"|-?[0-9][0-9.e+-]*|true|false)' <<<"$col_defaults")
  echo "$pass" >>"$WORK/readme_passes"
done < <(sed -n '/^### How the defaults were chosen/,/^## /p' README.md | grep '^| `')
n_api=$(sort -u "$WORK/lua_api_passes" 2>/dev/null | wc -l)
n_readme=$(sort -u "$WORK/readme_passes" 2>/dev/null | wc -l)
[ "$n_api" -ge 8 ] && pass "the docs' signatures give defaults of $n_api passes ($checked values), each as the code has it" \
  || fail "the docs' defaults" "only $n_api passes found in signatures"
[ "$n_readme" -ge 6 ] && pass "the README's table of defaults covers $n_readme passes, each as the code has it" \
  || fail "README defaults" "only $n_readme passes found in its table"
# The check itself catches a stale value.
[ "$(default_of photon_caustics texture)" = 512 ] && ! same 256 512 && same 0.020 0.02 \
  && pass "the comparison refuses a stale value" || fail "the comparison" "does not tell 256 from 512"
finish
