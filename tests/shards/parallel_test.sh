#!/usr/bin/env bash
# scripts/parallel-render.sh end to end: 3 parts with GNU parallel, merged,
# equal bit for bit to one render whose passes are those parts; a rerun
# after losing a part renders only that part. Installs parallel if it is
# missing and apt-get can; else skips (exit 77).
#   parallel_test.sh WHISKER_BIN SOURCE_DIR
set -euo pipefail
whisker=$1 WHISKER_SOURCE=$2
source "$WHISKER_SOURCE/tests/shards/small_scene.sh"
skip() { echo "SKIP: $*"; exit 77; }
if ! command -v parallel >/dev/null; then
  [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null || skip "GNU parallel is not installed (apt-get install parallel)"
  echo "installing parallel"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends parallel >/dev/null 2>&1 ||
    { apt-get update -q >/dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends parallel >/dev/null 2>&1; } ||
    skip "cannot install GNU parallel"
fi
tmp=$(mktemp -d /tmp/whisker-parallel.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
small_scene "$tmp/room.json"

JOBS=2 WHISKER=$whisker "$WHISKER_SOURCE/scripts/parallel-render.sh" "$tmp/room.json" 9 3 "$tmp/out/room.exr"
"$whisker" --headless --quiet --scene "$tmp/room.json" --samples 0:9 --spp 3 --out-float "$tmp/single.pfm"
"$whisker" merge "$tmp/out/room.exr" --out "$tmp/merged.pfm"
cmp "$tmp/single.pfm" "$tmp/merged.pfm" || { echo "FAIL: the parallel merge differs from the single render"; exit 1; }
[ -s "$tmp/out/room.png" ] || { echo "FAIL: no PNG beside the merge"; exit 1; }

# Lose a part: the rerun renders only it, and the merge is the same again.
rm "$tmp/out/room.parts/part-1.exr"
log=$(WHISKER=$whisker "$WHISKER_SOURCE/scripts/parallel-render.sh" "$tmp/room.json" 9 3 "$tmp/out/room.exr")
echo "$log"
[ "$(grep -c -- '-> .*part-' <<<"$log")" = 1 ] || { echo "FAIL: the rerun rendered more than the lost part"; exit 1; }
"$whisker" merge "$tmp/out/room.exr" --out "$tmp/merged2.pfm"
cmp "$tmp/single.pfm" "$tmp/merged2.pfm" || { echo "FAIL: the rerun's merge differs"; exit 1; }
echo "parallel-render: merge of 3 parts equals the single render bit for bit"
