#!/usr/bin/env bash
# One `rad batch` shard per task of a Slurm job array: task k of N solves scenes k, k + N, ...
# of the list. Submit from the repository (the folder holding build/rad), e.g. 16 tasks:
#   sbatch --array=0-15 tools/cluster/slurm-array.sh OUTDIR SCENES.txt [rad batch options...]
# OUTDIR must be shared by the nodes. A requeued or repeated task skips the scenes already
# done with the same options; OUTDIR/batch.json collects every task's rows.
#SBATCH --job-name=rad-batch
#SBATCH --cpus-per-task=2
#SBATCH --output=rad-batch-%A_%a.log
#SBATCH --requeue
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: sbatch --array=0-N tools/cluster/slurm-array.sh OUTDIR SCENES.txt [options]" >&2
  exit 2
fi
out="$1" list="$2"
shift 2
# sbatch runs a copy of this script from its spool folder: find rad from where it was submitted.
rad="${RAD:-${SLURM_SUBMIT_DIR:-.}/build/rad}"
exec "$rad" batch "$out" "$list" --shard slurm --threads "${SLURM_CPUS_PER_TASK:-0}" "$@"
