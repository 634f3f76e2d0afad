#!/bin/bash
# A zline batch split over a Slurm job array of 8 tasks.
#
# Task SLURM_ARRAY_TASK_ID (0..7) renders the inputs whose index in the
# sorted list is SLURM_ARRAY_TASK_ID modulo 8 (`--shard I/8`, I = id + 1).
# The models and the output folder are on a shared file system. Every PNG is
# written to a temporary file and renamed when whole, and an existing PNG is
# skipped, so a task that dies (node failure, time limit) is resubmitted
# with `sbatch --array=ID docs/slurm-batch.sh` and renders only what its
# shard still lacks; rerunning the whole array is just as safe.
#
# Not run by zline's tests: adjust the partition, the paths and the sizes.
# Usage: sbatch docs/slurm-batch.sh
#SBATCH --job-name=zline-batch
#SBATCH --array=0-7
#SBATCH --cpus-per-task=4
#SBATCH --mem=4G
#SBATCH --time=02:00:00
#SBATCH --output=zline-batch-%A-%a.log

set -euo pipefail
N=8
zline batch --list "$HOME/models.txt" -o "$HOME/renders" \
    --size 1280x720 --ssaa 2 --quiet \
    --threads "${SLURM_CPUS_PER_TASK:-4}" \
    --shard $((SLURM_ARRAY_TASK_ID+1))/$N
