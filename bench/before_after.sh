#!/usr/bin/env bash
# A change's before/after on this machine, in one invocation: builds the benchmark examples of REV
# (the commit before the change) in a git worktree under target/before-after/, and of this
# checkout, then runs each side's single-run benchmark (examples/accuracy_speed, pinned to one
# core, medians of RUNS) and design-study benchmark (examples/throughput: the GA's evaluator one
# design at a time and in lanes, the paper's GA, long chains; both cores, medians of 3),
# alternating before, after, before, after, so that a drift of the machine shows in both.
# Usage: bash bench/before_after.sh REV [RUNS]   (RUNS default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
rev="${1:?usage: bash bench/before_after.sh REV [RUNS]}"
runs="${2:-5}"
base="target/before-after/$(git rev-parse --short "$rev")"
if [ ! -d "$base" ]; then
  git worktree add --detach "$base" "$rev"
fi
examples=(--example accuracy_speed --example throughput)
(cd "$base" && cargo build --release -q -p woodpile "${examples[@]}")
cargo build --release -q -p woodpile "${examples[@]}"
for round in 1 2; do
  for side in before after; do
    if [ "$side" = before ]; then dir="$base"; else dir=.; fi
    echo "== $side ($(cd "$dir" && git rev-parse --short HEAD)), round $round: one run, one core, medians of $runs"
    taskset -c 0 "$dir/target/release/examples/accuracy_speed" --runs "$runs"
    echo "== $side, round $round: design-study throughput, both cores"
    "$dir/target/release/examples/throughput" --runs 3
  done
done
