#!/bin/sh
# Regenerate every table and figure of docs/seed_study.md from a fresh install:
# (paper_formulation.toml runs the paper's equations on solve_ivp: about 30 s with JOBS=2)
#     sh examples/seed_study/run.sh            (from the repository root or anywhere)
# Archives and printed tables go to ./seed_study_results (or the folder given as $1);
# figures to docs/figures/seed_study and Markdown tables to docs/figures/seed_study/*.md.
# JOBS=2 sh examples/seed_study/run.sh runs two worker processes.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${1:-seed_study_results}
FIGS="$ROOT/docs/figures/seed_study"
mkdir -p "$OUT" "$FIGS"
for study in tables_2_3 table_4 single_block duration_check paper_formulation; do
    rockscreen sweep "$HERE/$study.toml" --jobs "${JOBS:-1}" \
        --out "$OUT/$study.h5" --figures "$FIGS" --markdown "$FIGS/$study.md" \
        > "$OUT/$study.txt"
    cat "$OUT/$study.txt"
done
# The floor-motion check of docs/seed_study.md (code floor spectra and the modal floor
# accelerogram against the paper's Fig. 8 statements):
python "$HERE/floor_check.py" > "$OUT/floor_check.txt"
cat "$OUT/floor_check.txt"
