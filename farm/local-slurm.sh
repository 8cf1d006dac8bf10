#!/bin/bash
# farm/local-slurm.sh start|stop: a one-node Slurm cluster on this machine,
# for trying the recipes of docs/farm.md and for CI (farm/check.sh). The
# port's; a real cluster has its own (docs/farm.md, "A real cluster").
#
# Debian 12's own packages (apt-get install slurmctld slurmd slurm-client
# munge), as root. Everything lives in one folder, $FARM_SLURM_DIR
# (default /tmp/farm-slurm): munged's key, socket and log, slurm.conf and
# cgroup.conf, the daemons' state, spool, logs and PID files; nothing under
# /etc or /run is touched, and `stop` ends only the daemons `start` began
# (by the PIDs it wrote). The clients find the cluster by
#   export SLURM_CONF=$FARM_SLURM_DIR/slurm.conf
# which `start` prints.
#
# What it takes on a plain machine (no systemd, cgroup v2 or none): munged
# started by hand as the munge user; the node line of slurm.conf from
# `slurmd -C`; ProctrackType=proctrack/linuxproc, TaskPlugin=task/none,
# JobAcctGatherType=jobacct_gather/none; and a cgroup.conf of
# CgroupPlugin=cgroup/v1 with a dummy CgroupMountpoint (Slurm 22.05 reads
# cgroup.conf whatever the plugins, has no `disabled`, and its cgroup/v2
# wants systemd).
set -euo pipefail

dir=${FARM_SLURM_DIR:-/tmp/farm-slurm}
# The ports: Slurm's defaults; set them when another cluster uses those.
ctld_port=${FARM_SLURMCTLD_PORT:-6817}
slurmd_port=${FARM_SLURMD_PORT:-6818}
export SLURM_CONF=$dir/slurm.conf

say() { echo "local-slurm: $*" >&2; }

# The PID a daemon wrote, if that process still runs.
running() {
  local pid
  pid=$(cat "$1" 2>/dev/null) || return 1
  [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null && echo "$pid"
}

# Stops the daemon of PID file $1 (TERM, then KILL after 10 s).
stop_daemon() {
  local pid i
  pid=$(running "$1") || { rm -f "$1"; return 0; }
  kill -TERM "$pid" 2>/dev/null || true
  for i in $(seq 100); do
    kill -0 "$pid" 2>/dev/null || { rm -f "$1"; return 0; }
    sleep 0.1
  done
  say "$(basename "$1" .pid) ($pid) did not stop on TERM: KILL"
  kill -KILL "$pid" 2>/dev/null || true
  rm -f "$1"
}

stop() {
  if [ -S "$dir/munge/munge.socket" ] && [ -f "$SLURM_CONF" ] && running "$dir/slurmctld.pid" >/dev/null; then
    # The jobs first, so that no task outlives its slurmd.
    scancel --quiet --full "--user=$(id -un)" 2>/dev/null || true
  fi
  stop_daemon "$dir/slurmd.pid"
  stop_daemon "$dir/slurmctld.pid"
  stop_daemon "$dir/munge/munged.pid"
  say "stopped (logs in $dir)"
}

need() {
  local missing=()
  for p in munged slurmctld slurmd sbatch; do
    command -v "$p" >/dev/null 2>&1 || [ -x "/usr/sbin/$p" ] || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    say "cannot run Slurm here: ${missing[*]} not installed (apt-get install slurmctld slurmd slurm-client munge)"
    exit 3
  fi
  if [ "$(id -u)" != 0 ]; then
    say "cannot run Slurm here: start it as root (munged runs as the munge user, the daemons as root)"
    exit 3
  fi
  id munge >/dev/null 2>&1 || { say "cannot run Slurm here: no user munge (the munge package makes it)"; exit 3; }
}

start() {
  need
  if running "$dir/slurmctld.pid" >/dev/null || running "$dir/munge/munged.pid" >/dev/null; then
    say "already running in $dir (farm/local-slurm.sh stop first)"
    exit 1
  fi
  # Whatever fails from here on (a daemon that does not start, a command
  # that fails under set -e), what was started is stopped.
  trap 'say "start failed: stopping what it started"; stop' EXIT
  # A fresh cluster: no jobs or node states of an earlier one.
  rm -rf "$dir/state" "$dir/spool"
  mkdir -p "$dir"/{munge,state,spool,cgroup}
  chmod 0755 "$dir"
  # munged: its own key, socket, PID, seed and log, in a folder of its own.
  # (munged wants the socket's folder open to all: the clients reach it.)
  chown munge:munge "$dir/munge"
  chmod 0755 "$dir/munge"
  if [ ! -s "$dir/munge/munge.key" ]; then
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  fi
  chown munge:munge "$dir/munge/munge.key"
  chmod 0600 "$dir/munge/munge.key"
  runuser -u munge -- /usr/sbin/munged \
    --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/munged.seed" \
    --log-file="$dir/munge/munged.log"

  local host node
  host=$(hostname -s)
  node=$(slurmd -C | head -n 1)
  cat >"$SLURM_CONF" <<CONF
# Written by farm/local-slurm.sh: a one-node cluster in $dir.
ClusterName=farm
SlurmctldHost=$host
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
MinJobAge=600
$node State=UNKNOWN
PartitionName=farm Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  cat >"$dir/cgroup.conf" <<CONF
# Slurm 22.05 reads this whatever its plugins; none of them uses cgroups here.
CgroupPlugin=cgroup/v1
CgroupMountpoint=$dir/cgroup
CONF
  slurmctld
  slurmd
  local i
  for i in $(seq 150); do
    if sinfo --noheader --states=idle --format=%N 2>/dev/null | grep -q .; then
      say "started: node $(sinfo --noheader --format='%N %c CPUs %T'); export SLURM_CONF=$SLURM_CONF"
      trap - EXIT
      return 0
    fi
    sleep 0.2
  done
  say "the node did not come up in 30 s; its logs:"
  tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" "$dir/munge/munged.log" >&2 || true
  exit 1
}

case ${1:-} in
  start) start ;;
  stop) stop ;;
  *) echo "usage: farm/local-slurm.sh start|stop" >&2; exit 2 ;;
esac
