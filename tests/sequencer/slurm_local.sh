#!/bin/bash
# A one-node Slurm on localhost for trying render-farm runs (the recipe in
# shared/notes/verified-on-this-machine.md): munge + slurmctld + slurmd.
#
#   tests/sequencer/slurm_local.sh start     install what is missing (apt), configure, start, wait for the node
#   tests/sequencer/slurm_local.sh status    sinfo
#   tests/sequencer/slurm_local.sh selftest  a 4-task job array (sbatch --array=0-3 --wait) must run every task
#   tests/sequencer/slurm_local.sh stop      stop the daemons this script started (by their pid files)
#
# Needs root. Writes /etc/slurm/slurm.conf (an existing one that this script
# did not write is kept as slurm.conf.hs-backup) and, if missing,
# /etc/munge/munge.key. State lives under /var/spool/hs-slurm.
set -euo pipefail

STATE=/var/spool/hs-slurm
CONF=/etc/slurm/slurm.conf
MARK="# written by hybridscape tests/sequencer/slurm_local.sh"
MUNGE_PID=/run/munge/munged.pid

die() { echo "slurm_local.sh: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "run as root"

install_packages() {
  if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    echo "installing slurm-wlm and munge ..."
    DEBIAN_FRONTEND=noninteractive apt-get install -y slurm-wlm munge >/dev/null
  fi
}

write_config() {
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  # RealMemory a little under the machine's (MB), or slurmd refuses to register.
  mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
  mkdir -p /etc/slurm "$STATE/ctld" "$STATE/d" "$STATE/log"
  if [ -f "$CONF" ] && ! grep -q "^$MARK" "$CONF"; then
    cp -n "$CONF" "$CONF.hs-backup"
  fi
  cat > "$CONF" <<CONF
$MARK
ClusterName=hs-local
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/d
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
ReturnToService=2
MaxArraySize=100001
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start_munge() {
  if [ -f "$MUNGE_PID" ] && kill -0 "$(cat "$MUNGE_PID")" 2>/dev/null; then return; fi
  if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  chown munge:munge /etc/munge/munge.key
  chmod 400 /etc/munge/munge.key
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  su -s /bin/sh munge -c "/usr/sbin/munged --pid-file=$MUNGE_PID" || die "munged did not start"
  echo "$MUNGE_PID" > "$STATE/munge.pidfile"  # remember that we started it
}

running() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

start() {
  install_packages
  write_config
  start_munge
  running "$STATE/slurmctld.pid" || /usr/sbin/slurmctld
  running "$STATE/slurmd.pid" || /usr/sbin/slurmd
  for _ in $(seq 1 60); do
    if sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then
      sinfo
      return 0
    fi
    sleep 0.5
  done
  sinfo || true
  die "the node did not become idle; see $STATE/log/"
}

stop_pidfile() {
  local f=$1
  if running "$f"; then
    local pid
    pid=$(cat "$f")
    kill "$pid"
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  fi
  rm -f "$f"
}

stop() {
  stop_pidfile "$STATE/slurmd.pid"
  stop_pidfile "$STATE/slurmctld.pid"
  # munged only if this script started it.
  if [ -f "$STATE/munge.pidfile" ]; then
    stop_pidfile "$(cat "$STATE/munge.pidfile")"
    rm -f "$STATE/munge.pidfile"
  fi
  echo "stopped"
}

selftest() {
  local dir
  dir=$(mktemp -d)
  chmod 755 "$dir"
  cat > "$dir/array.sbatch" <<'JOB'
#!/bin/bash
#SBATCH --job-name=hs-selftest
#SBATCH --array=0-3
#SBATCH --output=%x_%A_%a.out
echo "task $SLURM_ARRAY_TASK_ID on $(hostname)"
JOB
  (cd "$dir" && sbatch --wait array.sbatch)
  local n
  n=$(cat "$dir"/hs-selftest_*.out | grep -c '^task ')
  cat "$dir"/hs-selftest_*.out
  rm -rf "$dir"
  [ "$n" = 4 ] || die "expected 4 array tasks, $n ran"
  echo "selftest: all 4 array tasks ran"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) sinfo; squeue ;;
  selftest) selftest ;;
  *) echo "usage: $0 start|status|selftest|stop" >&2; exit 2 ;;
esac
