# Sourced by the install tests. Needs $build (the build folder) and $src (the
# source tree). Gives $tmp (removed at exit), fail, and install_prefix.

tmp=$(mktemp -d "${TMPDIR:-/tmp}/whisker-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# install_prefix DIR: `cmake --install` of the build into a staging prefix,
# then moved to DIR: the installed tree works wherever it ends up.
install_prefix() {
  cmake --install "$build" --prefix "$tmp/staging" >"$tmp/install.log" 2>&1 ||
    { cat "$tmp/install.log" >&2; fail "cmake --install failed"; }
  mkdir -p "$(dirname "$1")"
  mv "$tmp/staging" "$1"
}

# hidden CMD...: runs CMD with the source tree (which holds the build
# folder) hidden under an empty tmpfs, in a mount namespace of its own, and
# without the WHISKER_* variables; from an empty working folder. Where mount
# namespaces are not allowed (a chroot, many containers), runs it with the
# variables unset only; the note saying so goes to the test's own log, once,
# never into the output of CMD that a test then reads.
if ! unshare -rm true 2>/dev/null; then
  echo "note: no mount namespace here; the source tree stays visible" >&2
fi
hidden() {
  mkdir -p "$tmp/cwd"
  local clean=(env -u WHISKER_ASSETS -u WHISKER_SCENES -u WHISKER_SHADERS)
  if unshare -rm true 2>/dev/null; then
    (cd "$tmp/cwd" && "${clean[@]}" unshare -rm sh -c \
      'mount -t tmpfs none "$0" && test -z "$(ls -A "$0")" && exec "$@"' "$src" "$@")
  else
    (cd "$tmp/cwd" && "${clean[@]}" "$@")
  fi
}
