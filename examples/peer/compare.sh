#!/usr/bin/env bash
# Side-by-side timing: linkage's solvers and CasADi's generated fast_newton (gcc -O3) on the
# same points, from the same start, in the same run. Prints a Markdown table.
#   bash examples/peer/compare.sh [points.csv]
# Needs python3 with pip (installs casadi) and gcc.
set -euo pipefail
cd "$(dirname "$0")/../.."
points=${1:-examples/data/table_v_points.csv}
work=$(mktemp -d)
python3 -c "import casadi" 2>/dev/null || python3 -m pip install --quiet casadi >&2
python3 examples/peer/casadi_stewart.py "$work" 2>/dev/null
cp examples/peer/bench_casadi.c "$work/"
gcc -O3 -march=native -o "$work/bench_casadi" "$work/bench_casadi.c" "$work/stewart_casadi.c" -lm
cargo build --quiet --release --example stewart
stewart=target/release/examples/stewart
# The start: the home configuration as linkage refines it (legs 170 mm).
printf 't,L1,L2,L3,L4,L5,L6\n0,170,170,170,170,170,170\n' > "$work/home.csv"
"$stewart" solve --input "$work/home.csv" | tail -n 1 | cut -d, -f9-26 | tr ',' '\n' > "$work/home_v.txt"
# Only the normal points for the headline, all points after.
head -n 101 "$points" > "$work/normal.csv"
# The last column: the median over the rows of each row's fastest pass (preemption only ever
# adds time, so it is the steadier figure on a busy machine).
row() { python3 -c "import json,sys; d=json.loads(sys.argv[1]); print(f\"| {sys.argv[2]} | {d['points']} | {d['mean_us']:.2f} | {d['median_us']:.2f} | {d['p99_us']:.2f} | {d['best_of_passes_median_us']:.2f} |\")" "$1" "$2"; }
echo "| solver | points | mean µs | median µs | p99 µs | fastest pass, median µs |"
echo "|---|---|---|---|---|---|"
for set in normal all; do
  input=$([ $set = normal ] && echo "$work/normal.csv" || echo "$points")
  row "$("$work/bench_casadi" "$input" "$work/home_v.txt")" "CasADi fast_newton, C -O3 ($set points)"
  row "$("$stewart" bench --method nr --input "$input" --json)" "linkage NR ($set)"
  row "$("$stewart" bench --method nr --dense --input "$input" --json)" "linkage NR, dense-LU baseline ($set)"
  row "$("$stewart" bench --method nh --input "$input" --json)" "linkage NH ($set)"
  row "$("$stewart" bench --method ph --input "$input" --json)" "linkage PH ($set)"
done
"$stewart" trajectory --out "$work/trajectory.csv" --seconds 2
row "$("$stewart" bench --method ph --track --input "$work/trajectory.csv" --json)" "linkage tracker, 1 kHz trajectory"
row "$("$stewart" bench --method nr --track --input "$work/trajectory.csv" --json)" "linkage NR from previous sample, 1 kHz"
echo
accuracy=$("$work/bench_casadi" "$points" "$work/home_v.txt")
python3 - "$accuracy" <<'PY'
import json, sys
d = json.loads(sys.argv[1])
print(f"CasADi on all points: {d['failed']} failed, {d['off_truth']} off the true pivots, mean relative error of the rest {d['mean_rel_error_ok']:.1e}")
PY
rm -rf "$work"
