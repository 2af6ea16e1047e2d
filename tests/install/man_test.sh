#!/bin/bash
# The man page renders without warnings and names every option that
# `whisker --help` and `whisker merge --help` list, and every exit code.
#   man_test.sh WHISKER_BIN PAGE (the page as built: the settings written in)
set -uo pipefail
bin=$1 page=$2
fail() { echo "FAIL: $*" >&2; exit 1; }
warnings=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l "$page" 2>&1 >/dev/null)
[ -z "$warnings" ] || fail "man warns: $warnings"
# The page's source with roff's \- as -, for plain searching.
text=$(sed 's/\\-/-/g' "$page")
options=$( { "$bin" --help; "$bin" merge --help; } | grep -oE -- '--[a-z][a-z-]*' | sort -u)
[ "$(echo "$options" | wc -l)" -gt 30 ] || fail "too few options in --help: $options"
missing=
for o in $options; do
  grep -qE -- "(^|[^a-z-])$o([^a-z-]|$)" <<<"$text" || missing+=" $o"
done
[ -z "$missing" ] || fail "options in --help but not in whisker.1:$missing"
for code in 0 1 2 3 128+; do
  grep -qE "^\.B[I]? $code" <<<"$text" || fail "exit code $code not in EXIT STATUS"
done
for s in "SCENE FILES" "EXIT STATUS" ENVIRONMENT FILES; do
  grep -qx "\.SH $s" <<<"$text" || fail "no section $s"
done
echo "man page OK: $(echo "$options" | wc -l) options"
