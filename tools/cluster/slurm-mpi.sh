#!/usr/bin/env bash
# One scene solved by every task of a Slurm job, one MPI rank per task (rad built with Open MPI;
# mpirun takes the nodes and tasks from the allocation). Submit from the repository (the folder
# holding build/rad), e.g. 8 nodes of 16 cores, one rank per node:
#   sbatch --nodes=8 --ntasks-per-node=1 --cpus-per-task=16 tools/cluster/slurm-mpi.sh \
#     SCENE OUTPUT [rad options...]
# The scene must be readable on every node; rank 0 writes OUTPUT (and --image, --stats-json,
# --checkpoint files). With --checkpoint on a shared file system a requeued job resumes.
#SBATCH --job-name=rad-mpi
#SBATCH --output=rad-mpi-%j.log
#SBATCH --requeue
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: sbatch --ntasks=N tools/cluster/slurm-mpi.sh SCENE OUTPUT [options]" >&2
  exit 2
fi
# sbatch runs a copy of this script from its spool folder: find rad from where it was submitted.
rad="${RAD:-${SLURM_SUBMIT_DIR:-.}/build/rad}"
exec mpirun --bind-to none "$rad" "$@" --threads "${SLURM_CPUS_PER_TASK:-1}"
