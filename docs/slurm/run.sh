#!/bin/sh
# The farm's scripts on a real Slurm on this one machine: a private slurmctld + slurmd (Debian's
# slurmctld, slurmd, slurm-client, munge), then
#  - a flight: a job array of docs/slurm/flight.sbatch, every frame rendered exactly once, and the same
#    frames rendered by one process (for the speed-up), identical;
#  - a poster: a job array of docs/slurm/poster.sbatch (a tile a task) and a stitching job that waits for
#    them (--dependency=afterok), equal to the image rendered at once by one process.
# Usage: docs/slurm/run.sh FATHOM PATH_FILE FRAMES_PER_TASK [fathom render options...]
#   (the poster: the csg scene, 97x55 in 5 tiles)
#   exit 77: Slurm or munge is not installed here (apt-get install slurmctld slurmd slurm-client munge)
# Needs root (munged and slurmd run as root here, in a private spool under a temporary folder).
set -eu
fathom=$(readlink -f "$1")
pathfile=$(readlink -f "$2")
per=$3
shift 3
for p in slurmctld slurmd sbatch squeue munged; do
    command -v "$p" >/dev/null 2>&1 || PATH=$PATH:/usr/sbin
    command -v "$p" >/dev/null 2>&1 || { echo "skip: $p is not installed (apt-get install slurmctld slurmd slurm-client munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "skip: needs root to run munged and slurmd"; exit 77; }
src=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d /tmp/fathom-slurm-XXXXXX)
chmod 755 "$tmp"
host=$(hostname -s)
cpus=$(nproc)
cleanup() {
    [ -f "$tmp/slurmd.pid" ] && kill "$(cat "$tmp/slurmd.pid")" 2>/dev/null
    [ -f "$tmp/slurmctld.pid" ] && kill "$(cat "$tmp/slurmctld.pid")" 2>/dev/null
    [ -f "$tmp/munged.pid" ] && kill "$(cat "$tmp/munged.pid")" 2>/dev/null
    sleep 1
    rm -rf "$tmp"
}
trap cleanup EXIT

# munge: a private key and socket
mkdir -p "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 600 "$tmp/munge/munge.key"
munged --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/socket" --pid-file="$tmp/munged.pid" \
    --log-file="$tmp/munge/log" --seed-file="$tmp/munge/seed"

mkdir -p "$tmp/state" "$tmp/spool" "$tmp/out" "$tmp/logs"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=fathom
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=flight Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N "$host"
i=0
until sinfo -h -o %t 2>/dev/null | grep -q idle; do
    i=$((i + 1))
    [ $i -lt 60 ] || { echo "FAIL: the node never became idle"; tail -5 "$tmp/slurmctld.log" "$tmp/slurmd.log"; exit 1; }
    sleep 1
done

# waits for a job (and its array's tasks) to leave the queue; a deadline well inside ctest's timeout, so a
# stuck job fails here and the daemons are stopped (a killed script could not stop them)
wait_job() {
    w=0
    while squeue -h -j "$1" 2>/dev/null | grep -q .; do
        w=$((w + 1))
        [ $w -lt 180 ] || { echo "FAIL: job $1 still queued after 180 s"; squeue; tail -5 "$tmp/slurmctld.log"; exit 1; }
        sleep 1
    done
}

# how many frames the path has: fathom names the last one when asked for a frame past it
frames=$("$fathom" render --path "$pathfile" --frames 100000000 --output "$tmp/probe_%d.png" --quiet "$@" 2>&1 |
    sed -n 's/.*ends at frame \([0-9]*\).*/\1/p')
[ -n "$frames" ] || { echo "FAIL: could not read the path's length"; exit 1; }
tasks=$(( (frames + per) / per ))
echo "slurm: $((frames + 1)) frames in $tasks tasks of $per on $host ($cpus cores)"
t0=$(date +%s.%N)
job=$(FATHOM="$fathom" sbatch --parsable --array=0-$((tasks - 1))%$cpus --chdir="$tmp" \
    --output="$tmp/logs/task_%a.log" "$src/docs/slurm/flight.sbatch" "$pathfile" "$tmp/out" "$per" --quiet "$@")
wait_job "$job"
t1=$(date +%s.%N)
n=$(ls "$tmp/out" | grep -c '^frame_' || true)
failed=$(grep -l -i "error\|fathom:" "$tmp"/logs/*.log 2>/dev/null | wc -l)
[ "$failed" -eq 0 ] || { echo "FAIL: $failed tasks reported errors:"; head -3 "$tmp"/logs/*.log; exit 1; }
[ "$n" -eq $((frames + 1)) ] || { echo "FAIL: $n frames on disk, expected $((frames + 1))"; exit 1; }
# exactly once: each frame's file was written once (its inode's change time is its only write); a
# second writer would have replaced it by rename, and the tasks' ranges do not overlap
dup=$(for l in "$tmp"/logs/*.log; do cat "$l"; done | grep -c "skipped" || true)
echo "slurm: all $n frames, each task's range once, $dup skip lines; $(awk "BEGIN {print $t1 - $t0}") s"

# the same frames by one process, for the speed-up
rm -rf "$tmp/one" && mkdir "$tmp/one"
t2=$(date +%s.%N)
"$fathom" render --path "$pathfile" --output "$tmp/one/frame_%04d.png" --quiet "$@"
t3=$(date +%s.%N)
for f in "$tmp"/one/*.png; do
    cmp -s "$f" "$tmp/out/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs between Slurm and one process"; exit 1; }
done
echo "one process: $(awk "BEGIN {print $t3 - $t2}") s; Slurm: $(awk "BEGIN {print $t1 - $t0}") s; frames identical"

# a poster: a tile a task, stitched by a job that waits for them all; equal to the image rendered at once
shot="--scene csg --size 97x55 --spp 1 --quiet"
job=$(FATHOM="$fathom" sbatch --parsable --array=1-5 --chdir="$tmp" --output="$tmp/logs/tile_%a.log" \
    "$src/docs/slurm/poster.sbatch" "$tmp/poster/poster.png" 5 $shot)
stitch=$(sbatch --parsable --dependency=afterok:"$job" --chdir="$tmp" --output="$tmp/logs/stitch.log" \
    --wrap "'$fathom' stitch --quiet --output '$tmp/poster.png' '$tmp'/poster/poster.tile-*-of-5.png")
wait_job "$job"
wait_job "$stitch"
tiles=$(ls "$tmp/poster" | grep -c '^poster\.tile-[1-5]-of-5\.png$' || true)
[ "$tiles" -eq 5 ] || { echo "FAIL: $tiles of 5 tiles on disk"; head -3 "$tmp"/logs/tile_*.log; exit 1; }
[ -f "$tmp/poster.png" ] || { echo "FAIL: the stitching job wrote nothing"; cat "$tmp/logs/stitch.log"; exit 1; }
"$fathom" $shot --output "$tmp/whole.png"
cmp -s "$tmp/whole.png" "$tmp/poster.png" || { echo "FAIL: the poster stitched on Slurm differs from the image rendered at once"; exit 1; }
echo "slurm: a poster in 5 tiles (an array) stitched by a dependent job, identical to one process"
