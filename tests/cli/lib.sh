# Helpers for the command-line tests: `bash X_test.sh CAUSTICA ROOT`.
set -u
CAUSTICA=$1
ROOT=$2
cd "$ROOT"
WORK=$(mktemp -d /tmp/caustica-cli.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
PASSED=0
FAILED=0

pass() { PASSED=$((PASSED + 1)); echo "ok   $1"; }
fail() { FAILED=$((FAILED + 1)); echo "FAIL $1: $2"; }

# expect_error NAME EXIT_CODE TEXT OUTPUT_THAT_MUST_NOT_EXIST -- command...
# The command must exit with EXIT_CODE, print TEXT on stderr's first line,
# and leave OUTPUT (a file or "-") unwritten, temporary files included.
expect_error() {
  local name=$1 code=$2 text=$3 output=$4
  shift 5
  local err="$WORK/stderr"
  "$@" >"$WORK/stdout" 2>"$err"
  local rc=$?
  local first
  first=$(head -n 1 "$err")
  if [ "$rc" != "$code" ]; then
    fail "$name" "exit $rc, expected $code (stderr: $first)"
  elif ! grep -qF -- "$text" <<<"$first"; then
    fail "$name" "first line of stderr '$first' lacks '$text'"
  elif [ "$output" != "-" ] && ls "$output"* >/dev/null 2>&1; then
    fail "$name" "left output behind: $(ls "$output"*)"
  elif [ "$output" != "-" ] && ls "$(dirname "$output")/.$(basename "$output")"* >/dev/null 2>&1; then
    fail "$name" "left a temporary behind: $(ls "$(dirname "$output")/.$(basename "$output")"*)"
  elif grep -qiE "segmentation|abort|core dumped" "$err"; then
    fail "$name" "crashed: $(cat "$err")"
  else
    pass "$name"
  fi
}

finish() {
  echo "$PASSED passed, $FAILED failed"
  [ "$FAILED" = 0 ]
}

# metric NAME LINE: one value from `caustica compare`'s key=value line.
metric() { tr ' ' '\n' <<<"$2" | sed -n "s/^$1=//p"; }
