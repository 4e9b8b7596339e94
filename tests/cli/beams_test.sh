# beam_caustics' report under --timings (beams, prisms, the fragments the
# bounding volumes rasterized: the paper's fill rate, §4.3), and the
# paper's claim about its bounding volumes: the six-triangle volumes
# rasterize fewer fragments than Ernst et al.'s prisms for the same beams
# (a glass ball focusing into fog, where the prisms of focused beams are
# loosest, Fig. 6).
source "$(dirname "$0")/lib.sh"
report() {
  "$CAUSTICA" render tests/scenes/fog.lua --set ball=true --set technique=beams --set volumes="$1" \
    --size 96x96 --timings -o "$WORK/$1.pfm" 2>"$WORK/$1.err" | grep -E "^  [0-9]+ beams" | head -n 1
}
tight=$(report tight)
prism=$(report prism)
re='^  ([0-9]+) beams \(([0-9]+) prisms\) from ([0-9]+) cells, ([0-9]+) fragments'
if [[ $tight =~ $re ]]; then
  tb=${BASH_REMATCH[1]} tp=${BASH_REMATCH[2]} tf=${BASH_REMATCH[4]}
  pass "--timings reports beams, prisms and fragments ($tight)"
else
  fail "--timings report" "no beam line: '$tight' ($(head -c 300 "$WORK/tight.err"))"
  tb=0 tp=0 tf=0
fi
if [[ $prism =~ $re ]]; then
  pb=${BASH_REMATCH[1]} pp=${BASH_REMATCH[2]} pf=${BASH_REMATCH[4]}
else
  fail "--timings report (prisms)" "no beam line: '$prism'"
  pb=0 pp=0 pf=0
fi
[ "$tb" -gt 0 ] && [ "$tb" = "$pb" ] && pass "the same beams either way ($tb)" || fail "beam counts" "tight $tb, prism $pb"
[ "$pp" = "$pb" ] && [ "$tp" -lt "$tb" ] && pass "volumes=prism uses prisms only; tight falls back on $tp of $tb" \
  || fail "prism fallback" "tight $tp of $tb, prism $pp of $pb"
[ "$tf" -gt 0 ] && [ "$tf" -lt "$pf" ] && pass "tight volumes rasterize fewer fragments ($tf against $pf)" \
  || fail "fill rate" "tight $tf, prism $pf fragments"
finish
