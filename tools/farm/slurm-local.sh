#!/bin/sh
# slurm-local.sh: a single-node Slurm on this machine, every file of it in one folder (no systemd, no
# cgroups, no accounting database), for `pacifica farm --engine slurm` without a cluster and for the tests.
#
#   tools/farm/slurm-local.sh start DIR [GPUS]   munged, slurmctld and slurmd with their state, logs and
#                                                sockets in DIR; GPUS > 0 declares that many GPUs (GRES):
#                                                real ones where /dev/nvidiaN exist, else fake devices
#                                                (device nodes in DIR) that only hand out
#                                                CUDA_VISIBLE_DEVICES
#   tools/farm/slurm-local.sh stop DIR           stops them (by the pids in their pid files)
#
# After `start`, every Slurm client command needs SLURM_CONF=DIR/slurm.conf (the script prints the line).
# Ports 16817/16818 (not Slurm's defaults, so a real Slurm on the machine is left alone). Runs as root or
# as the user that owns DIR (SlurmUser/SlurmdUser are that user). docs/SCALE.md.
set -eu

usage() {
    echo "usage: $0 start DIR [GPUS] | stop DIR" >&2
    exit 2
}

[ $# -ge 2 ] || usage
cmd=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)
gpus=${3:-0}

stop() {
    for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
        [ -f "$pidfile" ] || continue
        pid=$(cat "$pidfile")
        if [ -n "$pid" ] && kill "$pid" 2>/dev/null; then
            i=0
            while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do
                sleep 0.1
                i=$((i + 1))
            done
            kill -9 "$pid" 2>/dev/null || true
        fi
        rm -f "$pidfile"
    done
}

start() {
    for tool in munged slurmctld slurmd sinfo; do
        command -v "$tool" >/dev/null 2>&1 || {
            echo "slurm-local: $tool not found: install slurmctld slurmd slurm-client munge" >&2
            exit 1
        }
    done
    user=$(id -un)
    mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
    chmod 700 "$dir/munge"
    if [ ! -f "$dir/munge/munge.key" ]; then
        head -c 1024 /dev/urandom >"$dir/munge/munge.key"
        chmod 400 "$dir/munge/munge.key"
    fi
    munged -f --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" \
        --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/munge.seed"
    node=$(slurmd -C | head -n 1)
    gres_node=""
    : >"$dir/gres.conf"
    if [ "$gpus" -gt 0 ]; then
        gres_node=" Gres=gpu:$gpus"
        last=$((gpus - 1))
        if [ -e /dev/nvidia0 ] && [ -e "/dev/nvidia$last" ]; then
            echo "Name=gpu File=/dev/nvidia[0-$last]" >"$dir/gres.conf"
        else
            # Slurm wants a character device per GPU: nodes with /dev/null's numbers (mknod, root).
            i=0
            while [ $i -lt "$gpus" ]; do
                rm -f "$dir/fake-gpu$i"
                mknod "$dir/fake-gpu$i" c 1 3 || {
                    echo "slurm-local: cannot make a fake GPU device node (mknod needs root)" >&2
                    exit 1
                }
                i=$((i + 1))
            done
            echo "Name=gpu File=$dir/fake-gpu[0-$last]" >"$dir/gres.conf"
        fi
    fi
    cat >"$dir/slurm.conf" <<EOF
ClusterName=pacifica-local
SlurmctldHost=$(hostname -s)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MaxArraySize=100001
MaxJobCount=200000
SchedulerParameters=defer_batch=0
MinJobAge=600
GresTypes=gpu
$node$gres_node State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
    export SLURM_CONF="$dir/slurm.conf"
    for daemon in slurmctld slurmd; do
        flags=""
        [ $daemon = slurmctld ] && flags="-i"
        # shellcheck disable=SC2086
        $daemon $flags -f "$SLURM_CONF" || {
            echo "slurm-local: $daemon did not start; its log:" >&2
            tail -n 20 "$dir/$daemon.log" >&2 || true
            stop
            exit 1
        }
    done
    i=0
    while [ "$(sinfo -h -o %T 2>/dev/null | head -n 1)" != "idle" ]; do
        i=$((i + 1))
        if [ $i -gt 300 ]; then
            echo "slurm-local: the node did not become idle in 30 s; logs in $dir" >&2
            tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
            stop
            exit 1
        fi
        sleep 0.1
    done
    echo "export SLURM_CONF=$dir/slurm.conf"
}

case "$cmd" in
start) start ;;
stop) stop ;;
*) usage ;;
esac
