#!/bin/bash
# The man page as installed: the page in packaging/whisker.1 with the render
# settings' options (between its BEGIN SETTINGS and END SETTINGS comments)
# written in from the settings table, as the built binary prints it. Run by
# the build (cmake/install.cmake):
#   scripts/update_man.sh BINARY PAGE OUT
set -euo pipefail
bin=$1 page=$2 out=$3
generated=$(mktemp)
trap 'rm -f "$generated" "$out.new"' EXIT
"$bin" --man-settings >"$generated"
awk -v generated="$generated" '
  /^\.\\" END SETTINGS/ { inside = 0 }
  !inside { print }
  /^\.\\" .*edit the table, not these lines/ {
    while ((getline line < generated) > 0) print line
    inside = 1
  }
' "$page" >"$out.new"
mv "$out.new" "$out"
