#!/usr/bin/env bash
# The run loop's time per evaluation at REV against the work tree, both
# builds timed in one run, interleaved: ROUNDS times, each build runs every
# row once, and each row keeps its best. A slow spell of the machine then
# falls on both builds alike (a stored baseline, taken under another load,
# cannot tell 5 % from the noise; BENCHMARKS.md, "The run loop's
# baseline").
#
#   lagrange-studies/benches/run_loop/compare.sh REV [ROUNDS] [--instructions] [--only TEXT] [--seed]
#
# The rows are benches/run_loop.rs's, which REV must have; with --seed,
# the seed double pendulum's runs by Dop853 and Dopri5 alone (seed/, a
# scratch crate that builds against any commit, older ones included).
# With --instructions (needs valgrind), also each row's instructions per
# evaluation under cachegrind, which the machine's load does not move.
# Builds REV in a temporary worktree; prints a markdown table, the ratio
# work tree / REV.
set -euo pipefail
rev=${1:?usage: compare.sh REV [ROUNDS] [--instructions] [--only TEXT] [--seed]}
shift
rounds=10
instructions=0
seed=0
only=()
while [ $# -gt 0 ]; do
  case $1 in
    --instructions) instructions=1 ;;
    --seed) seed=1 ;;
    --only)
      only=(--only "$2")
      shift
      ;;
    *) rounds=$1 ;;
  esac
  shift
done
here=$(cd "$(dirname "$0")" && pwd)
root=$(git rev-parse --show-toplevel)
work=$(mktemp -d)
cleanup() {
  git -C "$root" worktree remove --force "$work/base" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT
git -C "$root" worktree add --detach "$work/base" "$rev" >/dev/null

# The executable for the tree in $1, copied to $2.
build() {
  local exe
  if [ "$seed" = 1 ]; then
    local crate="$work/seed-$(basename "$2" .bin)"
    mkdir -p "$crate/src"
    sed "s|@LAGRANGE@|$1|" "$here/seed/Cargo.toml.in" >"$crate/Cargo.toml"
    cp "$here/seed/main.rs" "$crate/src/main.rs"
    local target="$root/target/run_loop_seed_$(basename "$2" .bin)"
    cargo build --release --quiet --manifest-path "$crate/Cargo.toml" --target-dir "$target"
    exe="$target/release/run_loop_seed"
  else
    # Each tree its own target directory: cargo names a workspace
    # member's build the same from any checkout, and would take one tree's
    # build for the other's.
    exe=$(cd "$1" && CARGO_TARGET_DIR="$root/target/run_loop_$(basename "$2" .bin)" cargo bench -p lagrange-studies --bench run_loop --no-run 2>&1 |
      sed -n 's/.*Executable .*(\(.*\)).*/\1/p' | tail -n 1)
    [ -n "$exe" ] || {
      echo "no run_loop bench built from $1" >&2
      exit 1
    }
    case $exe in /*) ;; *) exe="$1/$exe" ;; esac
  fi
  cp "$exe" "$2"
}
build "$work/base" "$work/base.bin"
build "$root" "$work/head.bin"

# One round of every row: key, evaluations, ns per evaluation.
rows() {
  if [ "$seed" = 1 ]; then
    "$1" 1 | awk -F'\t' '{ printf "seed double pendulum|%s\t%s\t%.3f\n", $1, $2, $3 * 1e6 / $2 }'
  else
    "$1" --bench --raw --rounds 1 "${only[@]}"
  fi
}
for _ in $(seq "$rounds"); do
  rows "$work/base.bin" >>"$work/base.tsv"
  rows "$work/head.bin" >>"$work/head.tsv"
done

# Instructions per evaluation of each row, counted by cachegrind.
count() {
  local bin=$1
  cut -f1,2 "$2" | sort -u | while IFS=$'\t' read -r key evals; do
    local args=(--bench --once --only "$key")
    if [ "$seed" = 1 ]; then
      read -r -a args <<<"${key#*|}"
    fi
    ir=$(valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null \
      "$bin" "${args[@]}" 2>&1 >/dev/null | sed -n 's/.*I *refs: *//p' | tr -d ',')
    printf '%s\t%s\n' "$key" "$(awk -v i="$ir" -v e="$evals" 'BEGIN{printf "%.1f", i/e}')"
  done
}
if [ "$instructions" = 1 ]; then
  command -v valgrind >/dev/null || {
    echo "--instructions needs valgrind" >&2
    exit 1
  }
  count "$work/base.bin" "$work/base.tsv" >"$work/base.ir"
  count "$work/head.bin" "$work/head.tsv" >"$work/head.ir"
else
  : >"$work/base.ir"
  : >"$work/head.ir"
fi

dirty=$(git -C "$root" diff --quiet HEAD || echo +)
echo "# $rev against the work tree ($(git -C "$root" rev-parse --short HEAD)$dirty), best of $rounds interleaved rounds, load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
echo
echo "| problem | method | evaluations | $rev (ns) | work tree (ns) | ratio | $rev (instructions) | work tree (instructions) |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
awk -F'\t' '
  FILENAME ~ /base.tsv$/ { if (!($1 in b) || $3 < b[$1]) b[$1] = $3; be[$1] = $2; if (!($1 in seen)) { seen[$1] = 1; order[n++] = $1 } next }
  FILENAME ~ /head.tsv$/ { if (!($1 in h) || $3 < h[$1]) h[$1] = $3; he[$1] = $2; next }
  FILENAME ~ /base.ir$/ { bi[$1] = $2; next }
  FILENAME ~ /head.ir$/ { hi[$1] = $2; next }
  END {
    for (i = 0; i < n; i++) {
      k = order[i]; split(k, p, "|")
      ev = (be[k] == he[k]) ? be[k] : be[k] " / " he[k]
      ratio = (k in h) ? sprintf("%.3f", h[k] / b[k]) : "-"
      printf "| %s | %s | %s | %.1f | %s | %s | %s | %s |\n", p[1], p[2], ev, b[k], (k in h) ? sprintf("%.1f", h[k]) : "-", ratio, (k in bi) ? bi[k] : "-", (k in hi) ? hi[k] : "-"
    }
  }' "$work/base.tsv" "$work/head.tsv" "$work/base.ir" "$work/head.ir"
