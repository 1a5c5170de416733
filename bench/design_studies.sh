#!/usr/bin/env bash
# Design-study throughput of `woodpile optimize`, the default (fast) settings against
# `--paper-settings` (the paper's RK4 at 0.1 µs), in one invocation on this machine:
#  - the breeder GA on the built-in paper-impact problem (seed 1): designs valued per second;
#  - NSGA-II on two objectives (transmitted force and total mass, 20 Table 1 positions, 20
#    generations): designs per second;
#  - a robust evaluation (`ga.robust = "mean"` over 8 samples of crossing angles and impact speed,
#    20 positions, population 20, 2 generations): designs × samples per second.
# Each study runs RUNS times per setting, the settings alternating so that a drift of the machine
# shows in both; the table gives medians and the ratio default / paper. Both cores.
# Usage: bash bench/design_studies.sh [RUNS]   (RUNS default 3)
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
cargo build --release -q -p woodpile-cli
bin="$PWD/target/release/woodpile"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/tradeoff20.toml" <<'TOML'
[design]
positions = 20
[ga]
objectives = ["transmitted-force", "total-mass"]
generations = 20
TOML
cat > "$work/robust20.toml" <<'TOML'
[design]
positions = 20
[ga]
population = 20
generations = 2
robust = "mean"
[uncertainty]
samples = 8
crossing_angle_deg = { sd = 2.0 }
impact_velocity_m_s = { uniform = [1.8, 2.2] }
TOML

# Designs (× samples) per second of one run directory's summary.json.
rate() {
  python3 - "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
designs = s.get("screenings") or s["evaluations"]
print(f"{designs * int(sys.argv[2]) / s['elapsed_s']:.1f} {designs} {s['elapsed_s']:.2f}")
PY
}

declare -A rates
studies=(breeder nsga2 robust)
for i in $(seq "$runs"); do
  for study in "${studies[@]}"; do
    for setting in default paper; do
      flag=(); [ "$setting" = paper ] && flag=(--paper-settings)
      out="$work/$study-$setting-$i"
      case $study in
        breeder) "$bin" optimize --scenario paper-impact --seed 1 --out "$out" "${flag[@]}" > /dev/null 2>&1; k=1 ;;
        nsga2) "$bin" optimize "$work/tradeoff20.toml" --out "$out" "${flag[@]}" > /dev/null 2>&1; k=1 ;;
        robust) "$bin" optimize "$work/robust20.toml" --out "$out" "${flag[@]}" > /dev/null 2>&1; k=8 ;;
      esac
      r=$(rate "$out" "$k")
      echo "$study $setting run $i: $r (rate, designs, seconds)"
      rates[$study-$setting]+="${r%% *} "
    done
  done
done

median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
echo
echo "| study | default | \`--paper-settings\` | ratio |"
echo "| --- | --- | --- | --- |"
for study in "${studies[@]}"; do
  d=$(echo "${rates[$study-default]}" | median)
  p=$(echo "${rates[$study-paper]}" | median)
  case $study in
    breeder) name="breeder GA, paper-impact, seed 1 (designs/s)" ;;
    nsga2) name="NSGA-II, force and mass, 20 generations (designs/s)" ;;
    robust) name="robust GA, mean over 8 samples (designs × samples/s)" ;;
  esac
  echo "| $name | $d | $p | $(python3 -c "print(f'{$d / $p:.1f}×')") |"
done
