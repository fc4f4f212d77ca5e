#!/usr/bin/env bash
# A crane-sim study on a Slurm cluster: one MPI rank per core, rank 0 hands out the cases and
# writes the case table (docs/studies.md). Submit from the repository with the study file and,
# optionally, the table's path:
#   sbatch scripts/slurm_study.sh configs/study_rope_swings.yaml out/swings.h5
# A job stopped by its time limit (Slurm sends SIGTERM, then SIGKILL after KillWait) leaves the
# rows finished so far in <table>.checkpoint; submitting the same job again resumes there.
#SBATCH --job-name=crane-study
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --cpus-per-task=1
#SBATCH --time=04:00:00
#SBATCH --signal=TERM@120
#SBATCH --output=crane-study-%j.log
set -euo pipefail
study="${1:?usage: sbatch scripts/slurm_study.sh STUDY.yaml [TABLE.h5]}"
table="${2:-$(basename "${study%.*}").h5}"
binary="${CRANESIM_BIN:-build/crane-sim}"
resume=()
[ -e "$table.checkpoint" ] && resume=(--resume)
# srun starts one crane-sim per task; each learns its rank from Slurm's PMI (Open MPI built with
# Slurm support: `srun --mpi=list` shows pmix). The binary, the study, its scene and the table's
# directory must be on a file system every node sees.
srun --mpi=pmix "$binary" study "$study" -o "$table" "${resume[@]}" --quiet
