#!/usr/bin/env bash
# Starts or stops a single-node Slurm 22.05 cluster (munged, slurmctld, slurmd) for tests, as root, without systemd.
#   tools/slurm_local.sh up DIR     writes DIR/slurm.conf, DIR/env (source it: SLURM_CONF), starts the daemons and
#                                   waits until the node is idle (at most 20 s)
#   tools/slurm_local.sh down DIR   stops only the daemons it started, by the pid files in DIR
# The node is `localhost` with this machine's CPUs and 90 % of its memory (RealMemory, so --mem requests are met).
# Facts behind the settings: ../shared/notes/slurm-single-node.md and docs/CLUSTER.md "A single-node Slurm".
set -euo pipefail

usage() { sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; }
[ $# -eq 2 ] || { usage >&2; exit 2; }
action=$1
dir=$2

stop_pid_file() {  # SIGTERM the process in pid file $1 and wait up to 10 s for it to exit
  local file=$1 pid
  [ -s "$file" ] || return 0
  pid=$(cat "$file")
  if kill -0 "$pid" 2>/dev/null; then
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$file"
}

case "$action" in
  down)
    [ -d "$dir" ] || exit 0
    stop_pid_file "$dir/slurmd.pid"
    stop_pid_file "$dir/slurmctld.pid"
    stop_pid_file "$dir/munged.pid"
    exit 0
    ;;
  up) ;;
  *) usage >&2; exit 2 ;;
esac

for tool in munged slurmctld slurmd sinfo; do
  command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || {
    echo "slurm_local.sh: $tool not found: bash tools/install_deps.sh installs slurmctld, slurmd, slurm-client, munge" >&2
    exit 2
  }
done
[ "$(id -u)" = 0 ] || { echo "slurm_local.sh: run as root (slurmd starts jobs as their user)" >&2; exit 2; }
export PATH="$PATH:/usr/sbin"

mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
chmod 0755 "$dir"   # munged refuses a socket in a folder not executable by everyone
mkdir -p "$dir/state" "$dir/spool" "$dir/log"

# munge: its own key, socket, pid and log in DIR
head -c 1024 /dev/urandom > "$dir/munge.key"
chmod 0400 "$dir/munge.key"
munged --key-file "$dir/munge.key" --socket "$dir/munge.socket" --pid-file "$dir/munged.pid" \
  --log-file "$dir/log/munged.log" --seed-file "$dir/munge.seed" --force

cpus=$(nproc)
mem_mb=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
cat > "$dir/slurm.conf" <<CONF
ClusterName=waamlocal
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
JobRequeue=1
MinJobAge=600
SchedulerType=sched/builtin
SlurmctldPort=${WAAM_SLURMCTLD_PORT:-16817}
SlurmdPort=${WAAM_SLURMD_PORT:-16818}
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
echo "export SLURM_CONF=$dir/slurm.conf" > "$dir/env"
export SLURM_CONF="$dir/slurm.conf"

slurmctld -i -f "$SLURM_CONF"
slurmd -N localhost -f "$SLURM_CONF"
for _ in $(seq 200); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  if [ "$state" = idle ]; then echo "slurm_local.sh: node localhost idle ($cpus CPUs, $mem_mb MB) in $dir"; exit 0; fi
  sleep 0.1
done
echo "slurm_local.sh: the node did not become idle within 20 s (state '${state:-none}'); logs in $dir/log" >&2
"$0" down "$dir"
exit 1
