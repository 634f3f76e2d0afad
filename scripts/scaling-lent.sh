#!/usr/bin/env bash
# Thread scaling on a machine with many cores (BENCHMARKS.md, issue 29):
# every benchmark scene at 1, 2, 4, 8 and 16 threads with the bands cut as
# each thread count chooses, then 8 and 16 threads alternately with the
# bands whole (--band-pieces 1) and cut, then the model of the frame from
# that machine's own 1 and 2 threads. About 100 s on a 16-core Xeon.
# Writes cut_a.md, whole_a.md, cut_b.md, whole_b.md, scaling.md and
# machine.txt into OUT (default: the current folder).
#   cargo build --release -p xtask
#   scripts/scaling-lent.sh [XTASK] [ASSETS]
# The xtask binary finds assets/bump/sphere.obj by the path it was built
# in: run it where that path holds the repository (or link it there).
set -uo pipefail
x=${1:-target/release/xtask}
a=(--assets "${2:-../shared/assets}")
out=${OUT:-.}
{ nproc; lscpu | grep -E "Model name|Thread|Socket|NUMA node\(s\)"; } >"$out/machine.txt"
"$x" bench "${a[@]}" --threads 1,2,4,8,16 --frames 9 | tee "$out/cut_a.md"
"$x" bench "${a[@]}" --threads 8,16 --frames 9 --band-pieces 1 | tee "$out/whole_a.md"
"$x" bench "${a[@]}" --threads 8,16 --frames 9 | tee "$out/cut_b.md"
"$x" bench "${a[@]}" --threads 8,16 --frames 9 --band-pieces 1 | tee "$out/whole_b.md"
"$x" scaling "${a[@]}" --rounds 2 --frames 9 --model 4,8,16 | tee "$out/scaling.md"
