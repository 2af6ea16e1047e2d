#!/bin/bash
# The Debian package (scripts/package.sh --no-build: cpack -G DEB of the
# installed build, nothing rebuilt); its files, its control
# fields (Depends from the linked libraries, the version --version prints),
# no maintainer scripts (so removing it removes every file it brought); then
# the unpacked package's binary renders from another folder, source hidden.
#   deb_test.sh BUILD_DIR SOURCE_DIR VERSION
set -uo pipefail
build=$1 src=$2 version=$3
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
source "$here/lib.sh"

WHISKER_BUILD=$build bash "$src/scripts/package.sh" --no-build "$tmp/pkg" >"$tmp/cpack.log" 2>&1 ||
  { cat "$tmp/cpack.log" >&2; fail "scripts/package.sh --no-build failed"; }
debs=("$tmp"/pkg/whisker_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || fail "no single whisker_*.deb: ${debs[*]}"
deb=${debs[0]}
arch=$(dpkg --print-architecture)
[ "$(basename "$deb")" = "whisker_${version}_$arch.deb" ] || fail "file name $(basename "$deb")"

dpkg-deb -c "$deb" | awk '{print $6}' >"$tmp/files"
for f in ./usr/bin/whisker ./usr/share/whisker/scenes/cat.json ./usr/share/whisker/cat.obj \
         ./usr/share/whisker/shaders/display.frag ./usr/share/doc/whisker/README.md \
         ./usr/share/man/man1/whisker.1.gz ./usr/share/applications/whisker.desktop \
         ./usr/share/icons/hicolor/256x256/apps/whisker.png; do
  grep -qxF "$f" "$tmp/files" || fail "$f not in the package"
done
# Nothing outside /usr, nothing from the build or the tests.
bad=$(grep -v '^\./usr/' "$tmp/files" | grep -vx '\./' || true)
[ -z "$bad" ] || fail "files outside /usr: $bad"
if grep -qE 'whisker_tests|whisker-bench|CMakeFiles|\.a$' "$tmp/files"; then fail "build files packaged"; fi

field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = whisker ] || fail "Package: $(field Package)"
[ "$(field Version)" = "$version" ] || fail "Version: $(field Version), expected $version"
[ "$(field Architecture)" = "$arch" ] || fail "Architecture: $(field Architecture)"
[ "$(field Section)" = graphics ] || fail "Section: $(field Section)"
depends=$(field Depends)
# The package names in Depends, one a line (alternatives too).
echo "$depends" | tr ',|' '\n\n' | sed 's/^ *//; s/ .*//' | grep -v '^$' >"$tmp/depends"
for p in libc6 'libstdc++6' libglfw3 'libopenexr-*'; do
  found=no
  # shellcheck disable=SC2053  # $p is a pattern
  while read -r d; do [[ $d == $p ]] && found=yes; done <"$tmp/depends"
  [ $found = yes ] || fail "Depends lacks $p: $depends"
done
# Every library the binary links comes from a package named in Depends.
dpkg-deb -x "$deb" "$tmp/root"
for lib in $(readelf -d "$tmp/root/usr/bin/whisker" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'); do
  path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64|64bit/ {print $NF; exit}')
  [ -n "$path" ] || path=$(ldconfig -p | awk -v l="$lib" '$1 == l {print $NF; exit}')
  [ -n "$path" ] || fail "$lib: not found on this system"
  pkg=$(dpkg -S "$(readlink -f "$path")" 2>/dev/null | head -1 | cut -d: -f1)
  [ -n "$pkg" ] || pkg=$(dpkg -S "$path" 2>/dev/null | head -1 | cut -d: -f1)
  [ -n "$pkg" ] || fail "$lib ($path): no package owns it"
  grep -qxF "$pkg" "$tmp/depends" || fail "$lib is in $pkg, not in Depends: $depends"
done
# No maintainer scripts or conffiles: dpkg alone adds and removes the files.
dpkg-deb --ctrl-tarfile "$deb" | tar -t | sed 's|^\./||' | grep -v '^$' | sort >"$tmp/control"
[ "$(tr '\n' ' ' <"$tmp/control")" = "control md5sums " ] ||
  fail "control archive holds more than control and md5sums: $(tr '\n' ' ' <"$tmp/control")"

# The packaged binary, unpacked elsewhere: version, a render, the man page.
out=$(hidden "$tmp/root/usr/bin/whisker" --version) || fail "--version failed"
[ "$out" = "whisker $version" ] || fail "--version: $out"
hidden "$tmp/root/usr/bin/whisker" --headless --quiet --scene diffuse-ball --frames 1 \
  --out "$tmp/cwd/ball.png" >"$tmp/render.log" 2>&1 || { cat "$tmp/render.log" >&2; fail "render failed"; }
python3 "$here/check_png.py" "$tmp/cwd/ball.png" 512 512 0.1 || fail "ball.png"
MANWIDTH=100 man -l "$tmp/root/usr/share/man/man1/whisker.1.gz" 2>/dev/null >"$tmp/man.txt"
grep -q "EXIT STATUS" "$tmp/man.txt" && grep -q "WHISKER_ASSETS" "$tmp/man.txt" ||
  fail "the packaged man page does not render: $(head -5 "$tmp/man.txt")"
echo "package OK: $(basename "$deb"); Depends: $depends"
