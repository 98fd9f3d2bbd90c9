#!/usr/bin/env bash
# Random faces through every stage, at length: tools/fuzz.sh [COUNT] [SEED...]
# (2800 faces of each of the seeds 1 to 5 by default: the 2000 of the five
# older families and 800 aerofoil and cascade faces). Builds first, writes
# each face that is not ok to fuzz_out/ with a line in fuzz_out/fuzz.log,
# prints the counts per seed and exits non-zero if any seed saw a crash, a
# hang, a broken invariant or an internal error.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
count="${1:-2800}"
shift || true
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
"$root/tools/build.sh"
status=0
for seed in "${seeds[@]}"; do
  "$root/build/bin/medialmesh_fuzz" --seed "$seed" --count "$count" --out "$root/fuzz_out" || status=1
done
exit "$status"
