# shellcheck shell=bash
# The shared preamble of the shell tests in tests/campaigns: strict mode, a scratch folder
# removed on exit, and helpers that fail with a message. A test sources it first,
#   source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
# then sets $fibrenet (the binary, its first argument), which the helpers that run it use.
set -euo pipefail

# Makes a scratch folder ($work), removed when the test exits, and enters it.
enter_scratch() {
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cd "$work"
}

fail() { echo "FAIL: $*" >&2; exit 1; }

# json EXPR < FILE: prints the Python expression EXPR over the JSON document d read from stdin.
json() { python3 -c "import json,sys; d=json.load(sys.stdin); print($1)"; }

# with_sleep SECONDS CAMPAIGN.toml: the campaign with analytic.sleep_s set to SECONDS (the sleep
# per evaluation changes no result, only how long there is to kill or read the campaign).
with_sleep() { sed "s/\"analytic.sleep_s\" = [0-9.]*/\"analytic.sleep_s\" = $1/" "$2"; }

# results DB CAMPAIGN: the stored candidates as CSV without wall times and reasons (columns 7
# and 8), the part of a campaign that must repeat exactly.
results() { "$fibrenet" db export --db "$1" --campaign "$2" --format csv | cut -d, -f1-6,9-; }

# expect_exit CODE TEXT COMMAND...: runs COMMAND with stdout in out.txt and stderr in err.txt;
# fails unless it exits with CODE and stderr matches the grep pattern TEXT ("" matches any).
expect_exit() {
  local want_rc=$1 want=$2 rc=0
  shift 2
  "$@" > out.txt 2> err.txt || rc=$?
  [ "$rc" = "$want_rc" ] || { cat err.txt >&2; fail "exit code $rc, expected $want_rc: $*"; }
  grep -q -- "$want" err.txt || { cat err.txt >&2; fail "message lacks '$want': $*"; }
}
