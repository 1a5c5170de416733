#!/usr/bin/env bash
# Issue 10's benchmark, in one invocation on this machine:
#  1. one run of the benchmark problem (docs/physics.md §9 chain, resonant, default impact, 2 ms) in
#     woodpile at several integrator settings, and in three independent peers at the same physics:
#     SciPy solve_ivp (bench/peers/scipy_chain.py), a tuned numba RK4 (bench/peers/numba_chain.py) and
#     LAMMPS from Debian's package when `lmp` is installed (bench/peers/lammps_chain.{py,in});
#     each with its transmitted-peak error against a converged reference, and the speed ratios at
#     equal accuracy (transmitted peak within 1e-5);
#  2. design-study throughput of the GA's evaluator, one design at a time and in SIMD lanes, on
#     1 and 2 threads, with each setting's worst objective error, and the cost per element of long
#     chains (crates/woodpile/examples/throughput.rs).
# Single-run timings are pinned to one core with taskset. Usage: bash bench/throughput.sh [RUNS]
# (RUNS = repetitions for the medians, default 5). Installs numpy, scipy and numba in bench/.venv.
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-5}"

cargo build --release -q -p woodpile --example accuracy_speed --example throughput
echo "== woodpile, one run, one core, medians of $runs runs =="
rust_out=$(taskset -c 0 target/release/examples/accuracy_speed --runs "$runs")
echo "$rust_out"
reference=$(echo "$rust_out" | sed -n 's/.*transmitted peak \([0-9.]*\) N.*/\1/p')

if [ ! -x bench/.venv/bin/python ] || ! bench/.venv/bin/python -c "import numba, scipy" 2>/dev/null; then
  python3 -m venv bench/.venv
  bench/.venv/bin/pip install -q --upgrade pip
  bench/.venv/bin/pip install -q numpy scipy numba
fi
py=bench/.venv/bin/python
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 NUMBA_NUM_THREADS=1
echo
echo "== SciPy solve_ivp peer, one core, medians of 3 runs =="
scipy_out=$(for m in DOP853 RK45; do
  taskset -c 0 "$py" bench/peers/scipy_chain.py --reference "$reference" --runs 3 --method "$m"
done)
echo "$scipy_out"
echo
echo "== numba RK4 peer, one core, medians of $runs runs =="
numba_out=$(taskset -c 0 "$py" bench/peers/numba_chain.py --reference "$reference" --runs "$runs" --dt 0.1e-6 0.25e-6 0.4e-6 0.5e-6)
echo "$numba_out"
lammps_out=""
if command -v lmp > /dev/null; then
  echo
  echo "== LAMMPS peer (velocity Verlet; Loop time), one core, medians of 3 runs =="
  lammps_out=$("$py" bench/peers/lammps_chain.py --reference "$reference" --runs 3 --dt 5e-8 1e-7 1.25e-7 1.5e-7)
  echo "$lammps_out"
else
  echo
  echo "(LAMMPS not installed: apt-get install lammps to add its row)"
fi

# Fastest setting of each whose transmitted peak is within 1e-5 of the reference. Rows:
# woodpile: name(2 words) median_ms median_ms_peaks rhs_evals transm_err worst_err;
# SciPy: name(2 words) median_ms rhs_evals transm_err; numba and LAMMPS: name(3 words) median_ms
# evals_or_steps transm_err.
fastest() { awk -v t="$1" -v e="$2" '$0 ~ t && $e+0 <= 1e-5 { if (m == "" || $(c)+0 < m) m = $(c)+0 } END { print (m == "" ? "none" : m) }' c="$3"; }
woodpile_rows='^(rk4|dopri5|rkn64|peak_tolerance) '
w_peaks=$(echo "$rust_out" | fastest "$woodpile_rows" 6 4)
w_full=$(echo "$rust_out" | fastest "$woodpile_rows" 6 3)
w_every=$(echo "$rust_out" | fastest "$woodpile_rows" 7 4)
s_best=$(echo "$scipy_out" | fastest 'rtol=' 5 3)
n_best=$(echo "$numba_out" | fastest '^numba rk4 ' 6 4)
l_best=$(echo "$lammps_out" | fastest '^lammps verlet ' 6 4)
echo
echo "fastest one run with the transmitted peak within 1e-5 (ms):"
echo "  woodpile, peaks only: $w_peaks   woodpile, 1 us samples: $w_full"
echo "  SciPy: $s_best   numba RK4: $n_best   LAMMPS: ${l_best}"
awk -v w="$w_peaks" -v s="$s_best" -v n="$n_best" -v l="$l_best" 'BEGIN {
  printf "  woodpile (peaks only) is %.0fx SciPy, %.1fx numba", s / w, n / w
  if (l != "none" && l != "") printf ", %.1fx LAMMPS", l / w
  printf "\n" }'
echo "fastest woodpile run with every contact peak within 1e-5 (peaks only, ms): $w_every"

echo
echo "== design-study throughput (both cores) =="
target/release/examples/throughput --runs 3
