#!/usr/bin/env bash
# Starts a single-node Slurm cluster on localhost (munged, slurmctld, slurmd in the background,
# configuration and state in a temporary directory), submits a sharded render of the sample
# Cornell box with samples/slurm/submit-render.sh (a 4-task array and the dependent merge job),
# and checks the merged pixels against a single render's, bit for bit. Stops exactly the daemons
# it started (by their pid files, after checking the process names).
# Needs root and Debian's munge, slurmctld, slurmd and slurm-client (scripts/install-deps.sh).
# Where Slurm cannot start it skips (exit 77), but fails under CI=true.
#   slurm_cluster_test.sh KDRENDER KDCONVERT KDBUILD SOURCE_DIR
set -euo pipefail
kdrender=$1 kdconvert=$2 kdbuild=$3 source=$4

cannot_start() {
  echo "slurm_cluster_test: cannot start Slurm: $1" >&2
  if [ "${CI:-}" = true ]; then
    echo "slurm_cluster_test: FAILED (CI=true: Slurm must run here)" >&2
    exit 1
  fi
  echo "slurm_cluster_test: skipped" >&2
  exit 77
}

[ "$(id -u)" -eq 0 ] || cannot_start "not root (munged and slurmd need it)"
for tool in munged mungekey munge unmunge slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" > /dev/null || cannot_start "no $tool (scripts/install-deps.sh installs munge and slurm-wlm)"
done
id munge > /dev/null 2>&1 || cannot_start "no munge user"

# Short path: the munge socket must stay under about 100 bytes.
T=$(mktemp -d /tmp/kdslurm.XXXXXX)
chmod 755 "$T"
started=()  # pid files of the daemons started here
stop_daemons() {
  local file pid name
  for file in "${started[@]}"; do
    name=${file##*/}
    name=${name%.pid}
    [ -f "$file" ] || continue
    pid=$(cat "$file")
    # Only a process that is still the daemon started here.
    if [ -n "$pid" ] && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ]; then
      kill "$pid"
      for _ in $(seq 50); do [ -d "/proc/$pid" ] || break; sleep 0.1; done
    fi
  done
}
cleanup() {
  local status=$?
  stop_daemons
  if [ $status -ne 0 ] && [ $status -ne 77 ]; then
    for log in "$T"/*.log "$T"/munge/munged.log "$T"/work/out.exr.logs/*.log; do
      [ -f "$log" ] && { echo "== $log"; tail -20 "$log"; }
    done
  fi
  rm -rf "$T"
  exit $status
}
trap cleanup EXIT

# munge: its own key, socket, pid, log and seed files, run as the munge user.
mkdir -p "$T/munge"
chown munge: "$T/munge"
chmod 755 "$T/munge"
runuser -u munge -- mungekey --create --keyfile="$T/munge/munge.key" > /dev/null ||
  cannot_start "mungekey failed"
chmod 600 "$T/munge/munge.key"
sock=$T/munge/sock
runuser -u munge -- munged --socket="$sock" --key-file="$T/munge/munge.key" --pid-file="$T/munge/munged.pid" \
  --log-file="$T/munge/munged.log" --seed-file="$T/munge/seed" || cannot_start "munged did not start"
started+=("$T/munge/munged.pid")
munge -S "$sock" -n | unmunge -S "$sock" > /dev/null || cannot_start "munge credentials do not round-trip"

free_port() { /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
node=$(hostname -s)
mkdir -p "$T/state" "$T/spool"
: > "$T/plugstack.conf"
cat > "$T/slurm.conf" <<CONF
ClusterName=kdraytest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=bf_interval=1,sched_min_interval=0,batch_sched_delay=0
ReturnToService=2
PlugStackConfig=$T/plugstack.conf
MailProg=/bin/true
$(slurmd -C | head -1) NodeAddr=127.0.0.1
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$T/slurm.conf
slurmctld -f "$SLURM_CONF" || cannot_start "slurmctld did not start"
started+=("$T/slurmctld.pid")
slurmd -f "$SLURM_CONF" || cannot_start "slurmd did not start"
started+=("$T/slurmd.pid")
for _ in $(seq 150); do
  [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && break
  sleep 0.2
done
[ "$(sinfo -h -o %t 2>/dev/null)" = idle ] || cannot_start "the node did not come up idle ($(sinfo -h -o %t 2>&1))"
echo "slurm_cluster_test: cluster up"

# The sharded render: 10 samples in 4 shards (3, 3, 2, 2), the tree from a cache folder, merged;
# and the same render whole, from the tree file.
mkdir -p "$T/work"
cd "$T/work"
"$kdconvert" "$source/samples/cornell-box.obj" box.kdscene --quiet
"$kdbuild" box.kdscene box.kdtree --quiet > /dev/null
"$kdbuild" --cache tree-cache box.kdscene --quiet > /dev/null  # the shards find the tree here
view=(--width 24 --height 20 --cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077 --seed 3)
ids=$(KDRENDER=$kdrender "$source/samples/slurm/submit-render.sh" box.kdscene tree-cache out.exr 4 10 "${view[@]}")
echo "slurm_cluster_test: submitted $ids"
merge=${ids##* }
"$kdrender" box.kdscene box.kdtree -o single.exr --spp 10 "${view[@]}" --quiet
for _ in $(seq 600); do
  [ -z "$(squeue -h 2>/dev/null)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h)" ] || { echo "slurm_cluster_test: jobs still queued: $(squeue -h)" >&2; exit 1; }
for k in 0 1 2 3; do
  [ -f "out.shard-$k.exr" ] || { echo "slurm_cluster_test: shard $k missing" >&2; exit 1; }
done
[ -f out.exr ] || { echo "slurm_cluster_test: merge job $merge wrote no out.exr" >&2; exit 1; }
# Pixels (every channel, the exact sums included) equal; metadata such as timings may differ.
idiff -fail 0 -failpercent 0 -warn 0 out.exr single.exr
echo "slurm_cluster_test: merged shards equal the single render bit for bit"
