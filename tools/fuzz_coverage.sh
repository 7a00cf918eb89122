#!/usr/bin/env bash
# Branch coverage the committed fuzz corpora reach: builds the replay harnesses of tests/fuzz
# with clang's source-based coverage (no sanitizers: only the counts matter), replays each
# corpus once (deterministic: no randomness in the harnesses, the plant's noise seeded), and
# reports per file (and per function) the branches llvm-cov counts as covered (each outcome
# of a condition is one branch, the issue's "edges"). tools/fuzz_coverage_doc.py writes the
# figures into docs/faults.md (--write-doc) or fails when they differ from the doc or a listed
# file is below its floor (--check-doc, CI).
# usage: tools/fuzz_coverage.sh [--write-doc | --check-doc] [OUTDIR]   (default build/fuzz-coverage)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
mode=
case "${1:-}" in
--write-doc | --check-doc) mode=$1; shift ;;
-*) echo "fuzz_coverage: unknown option '$1'" >&2; exit 2 ;;
esac
out=$(realpath -m "${1:-$here/build/fuzz-coverage}")
flags="-fprofile-instr-generate -fcoverage-mapping"
cmake -S "$here" -B "$out/build" -G "Unix Makefiles" -DCMAKE_C_COMPILER=clang \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fprofile-instr-generate" >/dev/null
targets=(ctl_step_fixed ctl_step_float drive link_replies)
cmake --build "$out/build" -j2 --target "${targets[@]/#/fuzz_replay_}" >/dev/null
rm -rf "$out/profiles"
mkdir -p "$out/profiles"
objects=()
for t in "${targets[@]}"; do
  corpora=("$here/tests/fuzz/corpus")
  case $t in
  drive) corpora=("$here/tests/fuzz/corpus_drive" "$here/tests/fuzz/corpus_drive_long") ;;
  link_replies) corpora=("$here/tests/fuzz/corpus_link_replies") ;;
  esac
  bin=$out/build/tests/fuzz/fuzz_replay_$t
  files=()
  for c in "${corpora[@]}"; do files+=("$c"/*); done
  # the host tool's error lines (malformed replies) into the log; shown if the replay fails
  LLVM_PROFILE_FILE="$out/profiles/$t.profraw" "$bin" "${files[@]}" >"$out/replay_$t.log" 2>&1 \
    || { tail -n 20 "$out/replay_$t.log" >&2; exit 1; }
  objects+=(-object "$bin")
done
llvm-profdata merge -sparse "$out"/profiles/*.profraw -o "$out/fuzz.profdata"
llvm-cov export -format=text -instr-profile="$out/fuzz.profdata" "${objects[@]}" \
  >"$out/coverage.json"
python3 "$here/tools/fuzz_coverage_doc.py" ${mode:+"$mode" "$here/docs/faults.md"} \
  --root "$here" "$out/coverage.json"
