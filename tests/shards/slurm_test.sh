#!/usr/bin/env bash
# scripts/slurm-render.sh on a real one-node Slurm cluster on this machine:
# munged, slurmctld and slurmd are started here with their configuration,
# state and logs in a temporary folder (other ports than the defaults), the
# job array and the dependent merge are submitted, and the merge is checked
# against a single-machine render of the same passes, bit for bit.
# Installs slurm-wlm and munge if they are missing and apt-get can; skips
# (exit 77, with the reason) if Slurm cannot be started. Needs root.
#   slurm_test.sh WHISKER_BIN SOURCE_DIR
set -euo pipefail
whisker=$1 WHISKER_SOURCE=$2
source "$WHISKER_SOURCE/tests/shards/small_scene.sh"
skip() { echo "SKIP: $*"; exit 77; }
start_time=$SECONDS

[ "$(id -u)" = 0 ] || skip "starting slurmctld, slurmd and munged needs root"
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
   ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  command -v apt-get >/dev/null || skip "slurm-wlm and munge are not installed and there is no apt-get"
  echo "installing slurm-wlm and munge"
  install() { DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends slurm-wlm munge >/dev/null 2>&1; }
  install || { apt-get update -q >/dev/null 2>&1 && install; } || skip "cannot install slurm-wlm and munge"
fi

tmp=$(mktemp -d /tmp/whisker-slurm.XXXXXX)
# Stop exactly the daemons started here (their pid files), then clean up.
cleanup() {
  local name pid
  for name in slurmd slurmctld munged; do
    [ -s "$tmp/$name.pid" ] || continue
    pid=$(cat "$tmp/$name.pid")
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done
  rm -rf "$tmp"
}
trap cleanup EXIT
show_logs() { for f in "$tmp"/*.log; do echo "--- $f"; tail -n 20 "$f"; done; }

# munge: a fresh key and a socket of our own.
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge.key"
munged --force --socket="$tmp/munge.sock" --key-file="$tmp/munge.key" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" ||
  { show_logs; skip "munged would not start"; }

# Two free ports for slurmctld and slurmd.
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port=$((20000 + RANDOM % 20000))
while ! port_free "$ctld_port" || ! port_free $((ctld_port + 1)); do ctld_port=$((ctld_port + 2)); done
host=$(hostname -s)
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=whiskertest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$((ctld_port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.sock
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=whisker Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -f "$SLURM_CONF" || { show_logs; skip "slurmctld would not start"; }
slurmd -f "$SLURM_CONF" || { show_logs; skip "slurmd would not start"; }
for _ in $(seq 60); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [[ $state == idle* ]] && break
  sleep 0.5
done
[[ ${state:-} == idle* ]] || { show_logs; skip "the Slurm node did not come up (state: ${state:-none})"; }
echo "slurm: one node ($host, $(nproc) CPUs) up after $((SECONDS - start_time)) s"

small_scene "$tmp/room.json"
jobs_start=$SECONDS
WAIT=1 WHISKER=$whisker timeout 300 "$WHISKER_SOURCE/scripts/slurm-render.sh" "$tmp/room.json" 12 3 \
  "$tmp/out/room.exr" || { show_logs; cat "$tmp"/out/room.parts/*.log 2>/dev/null; echo "FAIL: the Slurm jobs failed"; exit 1; }
echo "slurm: job array of 3 parts and the merge done in $((SECONDS - jobs_start)) s"
cat "$tmp"/out/room.parts/*.log
for i in 0 1 2; do
  grep -q "part-$i.exr" "$tmp/out/room.parts/part-$i.log" || { echo "FAIL: task $i left no log of its part"; exit 1; }
done
grep -q "merged 3 parts, samples 0:12" "$tmp/out/room.parts/merge.log" || { echo "FAIL: the merge job's log"; exit 1; }

"$whisker" --headless --quiet --scene "$tmp/room.json" --samples 0:12 --spp 4 --out-float "$tmp/single.pfm"
"$whisker" merge "$tmp/out/room.exr" --out "$tmp/merged.pfm"
cmp "$tmp/single.pfm" "$tmp/merged.pfm" || { echo "FAIL: the Slurm merge differs from the single render"; exit 1; }
echo "slurm: merge equals the single-machine render bit for bit; $((SECONDS - start_time)) s in all"
