#!/usr/bin/env bash
# Benches run interleaved against another commit: each named bench built
# at REV and in the work tree (each its own target directory), then run
# ROUNDS times, REV's build then the work tree's, so that a slow spell of
# the machine falls on both. Their outputs go to DIR (kept), one file a
# run: REV.BENCH.ROUND and tree.BENCH.ROUND, for the medians a note
# quotes; each round's lines are printed side by side as they come.
#
#   lagrange-studies/benches/run_loop/interleave.sh REV ROUNDS DIR BENCH... [-- ARGS]
#
# ARGS go to every run (e.g. criterion's `--warm-up-time 1
# --measurement-time 3` for `frame`); every bench gets `--bench`.
# BENCHMARKS.md, "The run loop's baseline", says which benches a change to
# the runtime's layers is checked with (issue 45: rhs_overhead, frame,
# ensemble).
set -euo pipefail
rev=${1:?usage: interleave.sh REV ROUNDS DIR BENCH... [-- ARGS]}
rounds=${2:?rounds}
out=${3:?output directory}
shift 3
benches=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do
  benches+=("$1")
  shift
done
[ $# -gt 0 ] && shift
args=("$@")
root=$(git rev-parse --show-toplevel)
work=$(mktemp -d)
cleanup() {
  git -C "$root" worktree remove --force "$work/base" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT
git -C "$root" worktree add --detach "$work/base" "$rev" >/dev/null
mkdir -p "$out"

# The executable of bench $2 built in the tree $1 into target directory $3.
build() {
  local exe
  exe=$(cd "$1" && CARGO_TARGET_DIR="$3" cargo bench -p lagrange-studies --bench "$2" --no-run 2>&1 |
    sed -n 's/.*Executable .*(\(.*\)).*/\1/p' | tail -n 1)
  [ -n "$exe" ] || {
    echo "no $2 bench built from $1" >&2
    exit 1
  }
  case $exe in /*) ;; *) exe="$1/$exe" ;; esac
  echo "$exe"
}
declare -A base head
for bench in "${benches[@]}"; do
  base[$bench]=$(build "$work/base" "$bench" "$root/target/interleave_base")
  cp "${base[$bench]}" "$work/base.$bench"
  head[$bench]=$(build "$root" "$bench" "$root/target/interleave_head")
  cp "${head[$bench]}" "$work/head.$bench"
done
echo "# $rev against the work tree ($(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD || echo +)), $rounds interleaved rounds, load average at the start $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
# Criterion's reports under the target directory, not beside the sources
# (a bench runs from its crate's folder, as `cargo bench` runs it).
export CARGO_TARGET_DIR="$root/target/interleave_runs"
for round in $(seq "$rounds"); do
  for bench in "${benches[@]}"; do
    (cd "$root/lagrange-studies" && "$work/base.$bench" --bench "${args[@]}") >"$out/$rev.$bench.$round" 2>&1
    (cd "$root/lagrange-studies" && "$work/head.$bench" --bench "${args[@]}") >"$out/tree.$bench.$round" 2>&1
    echo "round $round, $bench: $out/$rev.$bench.$round, $out/tree.$bench.$round"
  done
done
echo "load average at the end $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
