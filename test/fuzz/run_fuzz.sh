#!/usr/bin/env bash
# Runs one fuzz target for a bounded time from its seed corpus, or replays inputs through it.
#
#   run_fuzz.sh --fuzzer BIN --work DIR [--seconds N] [--seed S] [--dict FILE] [--cdr-seeds]
#               [--corpus-dir DIR]... [--keep-corpus] [SEED_FILE...]
#   run_fuzz.sh --fuzzer BIN --replay FILE...
#
# DIR/seeds gets the seed files (or, with --cdr-seeds, the target's own serialized samples);
# DIR/corpus the inputs libFuzzer finds (emptied first unless --keep-corpus); DIR/artifacts
# any crashing, leaking or slow input. Exits non-zero on any crash, leak, timeout, out of
# memory or sanitizer report, printing the input and the command that reproduces it.
set -euo pipefail

fuzzer="" work="" seconds=20 seed=1 dict="" cdr_seeds=0 keep=0 replay=0
extra_dirs=() seed_files=()
while (($#)); do
  case "$1" in
    --fuzzer) fuzzer="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --dict) dict="$2"; shift 2 ;;
    --cdr-seeds) cdr_seeds=1; shift ;;
    --corpus-dir) extra_dirs+=("$2"); shift 2 ;;
    --keep-corpus) keep=1; shift ;;
    --replay) replay=1; shift ;;
    *) seed_files+=("$1"); shift ;;
  esac
done
[ -x "$fuzzer" ] || { echo "run_fuzz: no fuzz target at '$fuzzer' (is build/fuzz built?)" >&2; exit 2; }

if ((replay)); then
  ((${#seed_files[@]})) || { echo "run_fuzz: --replay needs input files" >&2; exit 2; }
  exec "$fuzzer" -rss_limit_mb=2048 -timeout=10 "${seed_files[@]}"
fi

[ -n "$work" ] || { echo "run_fuzz: --work DIR is required" >&2; exit 2; }
mkdir -p "$work/seeds" "$work/corpus" "$work/artifacts"
((keep)) || rm -rf "${work:?}/corpus"/* "${work:?}/artifacts"/*
rm -rf "${work:?}/seeds"/*
if ((${#seed_files[@]})); then cp "${seed_files[@]}" "$work/seeds/"; fi
if ((cdr_seeds)); then STICKREP_FUZZ_WRITE_SEEDS="$work/seeds" "$fuzzer"; fi

args=(-seed="$seed" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048
      -print_final_stats=1 -artifact_prefix="$work/artifacts/")
[ -n "$dict" ] && args+=(-dict="$dict")
echo "run_fuzz: $fuzzer ${args[*]} $work/corpus $work/seeds ${extra_dirs[*]}"
status=0
"$fuzzer" "${args[@]}" "$work/corpus" "$work/seeds" "${extra_dirs[@]}" > "$work/fuzz.log" 2>&1 ||
  status=$?
grep -E "^(#[0-9]+ +(INITED|DONE)|stat::|Done [0-9]+ runs)" "$work/fuzz.log" || true
if ((status != 0)); then
  tail -n 60 "$work/fuzz.log"
  for a in "$work/artifacts"/*; do
    [ -e "$a" ] || continue
    echo "run_fuzz: failing input $a; reproduce with: $fuzzer $a"
  done
  exit "$status"
fi
