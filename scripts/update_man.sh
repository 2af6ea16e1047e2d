#!/bin/bash
# Rewrites the render settings' options in packaging/whisker.1 (between the
# BEGIN SETTINGS and END SETTINGS comments) from the settings table, as the
# built binary prints it:
#   scripts/update_man.sh build/whisker
# CliSettings.ManPageListsEveryRow fails until the page matches the table.
set -euo pipefail
bin=$1
page=$(dirname "$0")/../packaging/whisker.1
generated=$(mktemp)
trap 'rm -f "$generated" "$page.new"' EXIT
"$bin" --man-settings >"$generated"
awk -v generated="$generated" '
  /^\.\\" END SETTINGS/ { inside = 0 }
  !inside { print }
  /^\.\\" .*edit the table, not these lines/ {
    while ((getline line < generated) > 0) print line
    inside = 1
  }
' "$page" >"$page.new"
mv "$page.new" "$page"
