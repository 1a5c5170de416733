#!/usr/bin/env bash
# Fuzzes every target of woodpile's readers with AFL++ (cargo-afl) until each has run
# EXECS inputs (default 1,000,000), then prints per target: executions, edges covered, crashes
# and hangs (inputs over 1 s). Findings go to OUT (default crates/woodpile-fuzz/findings/,
# ignored by git); a crash or hang found is a bug: add its input to corpus/<target>/ once fixed.
#
#   cargo install cargo-afl                      # once
#   bash crates/woodpile-fuzz/run.sh [EXECS] [OUT] [TARGET...]
set -euo pipefail
execs="${1:-1000000}"
# OUT relative to where the script is called from; the default beside the targets.
out="$(realpath -m "${2:-$(dirname "$0")/findings}")"
cd "$(dirname "$0")"
shift $(( $# > 2 ? 2 : $# )) || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scenario lattice optimize_config npy table checkpoint fit uncertainty)
mkdir -p "$out"
export AFL_SKIP_CPUFREQ=1 AFL_NO_UI=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 AFL_NO_AFFINITY=1
cargo afl build --release --quiet
for t in "${targets[@]}"; do
  cargo afl fuzz -i "corpus/$t" -o "$out/$t" -E "$execs" -t 1000 "target/release/$t" > "$out-$t.log" 2>&1 || {
    echo "$t: afl-fuzz failed, see $out-$t.log"; exit 1; }
done
printf '%-16s %12s %10s %8s %6s\n' target executions coverage crashes hangs
for t in "${targets[@]}"; do
  s="$out/$t/default/fuzzer_stats"
  get() { awk -F' *: *' -v k="$1" '$1 == k {print $2}' "$s"; }
  printf '%-16s %12s %10s %8s %6s\n' "$t" "$(get execs_done)" "$(get bitmap_cvg)" "$(get saved_crashes)" "$(get saved_hangs)"
done
