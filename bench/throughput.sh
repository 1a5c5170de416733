#!/usr/bin/env bash
# Times the benchmark problem (docs/physics.md §9 chain, resonant, default impact, 2 ms) in woodpile and in
# an independent SciPy solve_ivp script, in the same invocation, and prints both tables and the
# speed ratio at equal accuracy (transmitted peak within 1e-5 of a converged reference).
# Usage: bash bench/compare_scipy.sh [RUNS]     (RUNS = runs per setting for the medians, default 7)
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-7}"

cargo build --release -q -p woodpile --example accuracy_speed
echo "== woodpile (Rust), one core, medians of $runs runs =="
rust_out=$(taskset -c 0 target/release/examples/accuracy_speed --runs "$runs")
echo "$rust_out"
reference=$(echo "$rust_out" | sed -n 's/.*transmitted peak \([0-9.]*\) N.*/\1/p')

if [ ! -x bench/.venv/bin/python ]; then
  python3 -m venv bench/.venv
  bench/.venv/bin/pip install -q --upgrade pip
  bench/.venv/bin/pip install -q numpy scipy
fi
echo
echo "== SciPy solve_ivp peer (bench/peers/scipy_chain.py), one core, medians of 3 runs =="
# Both of SciPy's explicit Runge-Kutta pairs; the faster one at equal accuracy is the baseline.
py_out=$(for m in DOP853 RK45; do
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 taskset -c 0 bench/.venv/bin/python bench/peers/scipy_chain.py --reference "$reference" --runs 3 --method "$m"
done)
echo "$py_out"

# Fastest setting of each whose transmitted peak is within 1e-5 of the reference. Rust rows:
# name(2 words) median_ms median_ms_peaks rhs_evals transm_err worst_peak_err; SciPy rows:
# name(2 words) median_ms rhs_evals transm_err.
rust_full=$(echo "$rust_out" | awk '/^(rk4|dopri5) / && $6+0 <= 1e-5 { if (m == "" || $3+0 < m) m = $3+0 } END { print m }')
rust_peaks=$(echo "$rust_out" | awk '/^(rk4|dopri5) / && $6+0 <= 1e-5 { if (m == "" || $4+0 < m) m = $4+0 } END { print m }')
py_best=$(echo "$py_out" | awk '/rtol=/ && $5+0 <= 1e-5 { if (m == "" || $3+0 < m) m = $3+0 } END { print m }')
echo
echo "fastest at transmitted-peak error <= 1e-5:"
echo "  woodpile, full 1 us sampling : ${rust_full} ms"
echo "  woodpile, peaks only         : ${rust_peaks} ms"
echo "  SciPy solve_ivp              : ${py_best} ms"
awk -v a="$py_best" -v b="$rust_full" -v c="$rust_peaks" 'BEGIN { printf "  speed-up: %.0fx (full sampling), %.0fx (peaks only)\n", a / b, a / c }'
