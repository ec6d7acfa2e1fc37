# shellcheck shell=bash
# A private one-node Slurm cluster for a test, on this machine. Sourced by
# tests that submit through sbatch (slurm.sh). Everything lives in one
# directory: munge key and socket, slurm.conf, state, spool, logs. The
# daemons run as root (SlurmUser=root) with proctrack/linuxproc and no
# cgroups, on free ports and the loopback address, so that they need
# nothing from the host's /etc (not even a resolvable host name) and do not
# meet another test's cluster.
#
#   slurm_start DIR   start munged, slurmctld and slurmd; wait for the node
#   slurm_stop        stop all three (safe to call twice, and from a trap)
#
# After slurm_start, SLURM_CONF points at DIR/slurm.conf, so sbatch, squeue
# and sacct talk to this cluster.

SLURM_DIR=""
SLURM_PIDS=()

# A TCP port nothing listens on (the kernel picks it; a race with another
# process is possible but harmless: the daemon would fail to start and say so).
slurm_free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("",0)); print(s.getsockname()[1])'
}

slurm_log_tail() {
  local f
  for f in "$SLURM_DIR"/munged.log "$SLURM_DIR"/slurmctld.log "$SLURM_DIR"/slurmd.log; do
    [ -f "$f" ] && { echo "--- $f (last lines)"; tail -n 15 "$f"; }
  done >&2
  return 0
}

slurm_start() {
  SLURM_DIR="$1"
  mkdir -p "$SLURM_DIR"/{state,spool,munge}
  chmod 700 "$SLURM_DIR/munge"
  local node cpus mem ctld_port d_port
  node="$(hostname -s)"
  # Enough slots for the coupler and a few driver ranks on a small machine:
  # the node declares at least 8 CPUs (config_overrides lets slurmd accept
  # more than it has; the ranks then share the real cores, as under mpirun
  # --oversubscribe).
  cpus="$(nproc)"
  [ "$cpus" -ge 8 ] || cpus=8
  mem="$(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo)"
  ctld_port="$(slurm_free_port)"
  d_port="$(slurm_free_port)"
  [ "$ctld_port" != "$d_port" ] || d_port=$((d_port + 1))

  # munge: a fresh key, its own socket; --force because it runs as root in
  # a directory it does not own the way it would like.
  dd if=/dev/urandom of="$SLURM_DIR/munge/munge.key" bs=1 count=1024 status=none
  chmod 400 "$SLURM_DIR/munge/munge.key"
  munged --force --key-file="$SLURM_DIR/munge/munge.key" \
    --socket="$SLURM_DIR/munge/munge.socket" --pid-file="$SLURM_DIR/munge/munged.pid" \
    --seed-file="$SLURM_DIR/munge/munged.seed" --log-file="$SLURM_DIR/munged.log" ||
    { slurm_log_tail; echo "slurm_lib: munged did not start" >&2; return 1; }
  SLURM_PIDS+=("$(cat "$SLURM_DIR/munge/munged.pid")")

  cat >"$SLURM_DIR/slurm.conf" <<EOF
ClusterName=pbmstest
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SLURM_DIR/munge/munge.socket
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool
SlurmctldPidFile=$SLURM_DIR/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/slurmd.pid
SlurmctldLogFile=$SLURM_DIR/slurmctld.log
SlurmdLogFile=$SLURM_DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$SLURM_DIR/slurm.conf"

  slurmctld -i -f "$SLURM_CONF" ||
    { slurm_log_tail; echo "slurm_lib: slurmctld did not start" >&2; return 1; }
  slurm_wait_file "$SLURM_DIR/slurmctld.pid" || { slurm_log_tail; return 1; }
  SLURM_PIDS+=("$(cat "$SLURM_DIR/slurmctld.pid")")
  slurmd -f "$SLURM_CONF" -N "$node" ||
    { slurm_log_tail; echo "slurm_lib: slurmd did not start" >&2; return 1; }
  slurm_wait_file "$SLURM_DIR/slurmd.pid" || { slurm_log_tail; return 1; }
  SLURM_PIDS+=("$(cat "$SLURM_DIR/slurmd.pid")")

  # The node is ready when sinfo reports it idle.
  local i state=""
  for i in $(seq 1 60); do
    state="$(sinfo -h -N -o '%t' 2>/dev/null | head -n 1)" || true
    [ "$state" = idle ] && return 0
    sleep 1
  done
  slurm_log_tail
  echo "slurm_lib: node $node not idle after 60 s (state '$state')" >&2
  return 1
}

slurm_wait_file() {
  local i
  for i in $(seq 1 50); do
    [ -s "$1" ] && return 0
    sleep 0.2
  done
  echo "slurm_lib: $1 did not appear" >&2
  return 1
}

slurm_stop() {
  local pid i
  # Last started first: slurmd, slurmctld, munged. Only the pids this test
  # started are signalled.
  for ((i = ${#SLURM_PIDS[@]} - 1; i >= 0; i--)); do
    pid="${SLURM_PIDS[$i]}"
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 1 50); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.2
    done
    kill -9 "$pid" 2>/dev/null || true
  done
  SLURM_PIDS=()
}
