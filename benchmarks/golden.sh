#!/bin/bash
# benchmarks/golden.sh OUTDIR: write the outputs a refactor or a speed-up must keep byte for byte: every
# example's `solve --json` (its own pose and --angle 77), the text tables, the full and poles sheets as SVG,
# the sweep's CSV and plot (about 134 files, 3 minutes here).
# Run from the checkout's root with PYTHONPATH=$PWD, once before and once after; compare with: diff -r A B
set -e
out=${1:?outdir}; mkdir -p "$out"
for f in velpoly/examples/*.toml; do
  s=$(basename "$f" .toml)
  python3 -m velpoly solve "$f" --json > "$out/$s.json" 2>/dev/null || echo "exit $?" > "$out/$s.json"
  python3 -m velpoly solve "$f" > "$out/$s.txt" 2>&1 || true
  python3 -m velpoly solve "$f" --angle 77 --json > "$out/$s.77.json" 2>/dev/null || echo "exit $?" > "$out/$s.77.json"
  for sh in full poles; do
    python3 -m velpoly draw "$f" --sheet $sh -o "$out/$s.$sh.svg" >/dev/null 2>&1 || echo "exit $?" > "$out/$s.$sh.svg.exit"
  done
  python3 -m velpoly sweep "$f" --csv "$out/$s.csv" -o "$out/$s.sweep.svg" >/dev/null 2>&1 || true
done
