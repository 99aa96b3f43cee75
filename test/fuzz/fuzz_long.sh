#!/usr/bin/env bash
# The longer fuzz run: every target (or the ones named) for SECONDS each, one after another,
# keeping its corpus in BUILD/fuzz-long/<target> from run to run (so a second run goes on
# where the first stopped). Prints each target's executions, and for a target that fails the
# failing input and the command that reproduces it; exits non-zero if any target failed.
#
#   bash test/fuzz/fuzz_long.sh BUILD SECONDS [SEED] [TARGET...]
set -euo pipefail
build="${1:?usage: fuzz_long.sh BUILD SECONDS [SEED] [TARGET...]}"
seconds="${2:?usage: fuzz_long.sh BUILD SECONDS [SEED] [TARGET...]}"
seed="${3:-1}"
shift $(($# < 3 ? $# : 3))
here="$(cd "$(dirname "$0")" && pwd)"
failed=()
[ -f "$build/fuzz/targets.tsv" ] || { echo "fuzz_long: build $build first" >&2; exit 2; }
while IFS=$'\t' read -r -a line; do
  name="${line[0]}"
  if (($#)) && [[ " $* " != *" $name "* ]]; then continue; fi
  echo "== $name: $seconds s, seed $seed"
  bash "$here/run_fuzz.sh" "${line[@]:1}" --work "$build/fuzz-long/$name" --seconds "$seconds" \
    --seed "$seed" --keep-corpus || failed+=("$name")
done < "$build/fuzz/targets.tsv"
if ((${#failed[@]})); then
  echo "fuzz_long: failed: ${failed[*]}"
  exit 1
fi
echo "fuzz_long: every target passed"
