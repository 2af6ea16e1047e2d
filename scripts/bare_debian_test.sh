#!/usr/bin/env bash
# Runs the README's test command on a bare Debian 12: a minimal system made
# by debootstrap (--variant=minbase: dpkg, apt and bash, nothing else), the
# project's committed tree copied in, then scripts/test.sh inside it as root.
# What that system lacks and the scripts do not install fails here, not on a
# user's machine.
#
#   scripts/bare_debian_test.sh [-- TEST.SH ARGS]   e.g. -- --normal
#
# Needs root (chroot, mounts) and the network to a Debian mirror
# ($WHISKER_DEBIAN_MIRROR, default http://deb.debian.org/debian).
# $WHISKER_BARE_DIR (default build-bare/ in the source tree) holds the
# pristine system as a tarball, made once and reused, and the system of the
# last run, made anew from it each time.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

mirror=${WHISKER_DEBIAN_MIRROR:-http://deb.debian.org/debian}
dir=${WHISKER_BARE_DIR:-$WHISKER_ROOT/build-bare}
args=()
[ "${1:-}" = -- ] && { shift; args=("$@"); }

[ "$(id -u)" -eq 0 ] || { whisker_log "needs root (chroot and mounts)"; exit 2; }
command -v debootstrap >/dev/null 2>&1 || {
  whisker_log "installing: debootstrap"
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap
}

root=$dir/root
mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[i]}" 2>/dev/null || true; done
}
trap cleanup EXIT
bind() { mkdir -p "$root$1" && mount --bind "$1" "$root$1" && mounted+=("$root$1"); }

mkdir -p "$dir"
if [ ! -f "$dir/minbase.tar" ]; then
  whisker_log "making a minbase Debian 12 (once)"
  rm -rf "$dir/make"
  debootstrap --variant=minbase bookworm "$dir/make" "$mirror" >"$dir/debootstrap.log" 2>&1 ||
    { tail -20 "$dir/debootstrap.log" >&2; whisker_log "debootstrap failed"; exit 1; }
  tar -C "$dir/make" -cf "$dir/minbase.tar.part" . && mv "$dir/minbase.tar.part" "$dir/minbase.tar"
  rm -rf "$dir/make"
fi

whisker_log "a fresh system from the tarball"
rm -rf "$root"
mkdir -p "$root"
tar -C "$root" -xf "$dir/minbase.tar"
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
# The committed tree, as a clean clone has it.
mkdir -p "$root/src"
git -C "$WHISKER_ROOT" archive HEAD | tar -C "$root/src" -xf -
for m in /proc /sys /dev /dev/pts; do bind "$m"; done

whisker_log "scripts/test.sh ${args[*]} in the bare system (log: $dir/test.log)"
set +e
chroot "$root" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  bash -c 'cd /src && exec bash scripts/test.sh "$@"' test.sh "${args[@]}" 2>&1 |
  tee "$dir/test.log"
rc=${PIPESTATUS[0]}
set -e
whisker_log "bare Debian 12: scripts/test.sh exit $rc"
exit "$rc"
