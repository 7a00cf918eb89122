#!/usr/bin/env bash
# Memory of the F28335 image, checked without TI's compiler (CI runs this), for both builds:
#   - stack: the deepest background path plus a nested control interrupt must fit the stack
#     the TI link reserves (--stack_size in cmake/ti-c2000-toolchain.cmake), with margin;
#   - placement: every function the control interrupt can reach runs from RAM (the flash linker
#     file's ramfuncs list), except what the build leaves in flash on purpose;
#   - RAM: that code (L0..L3), its constant tables and all static data (L4..L7) must fit their
#     blocks with margin.
# Compiles exactly the target's C sources (cmake/sources.cmake, target code paths as in the
# host link check) with arm-none-eabi-gcc, a 32-bit proxy for cl2000, twice per build: -O2
# with one section per function and -fcallgraph-info=su (sizes, stack frames), and -O2
# -fno-inline (the complete call graph of the period, whatever cl2000 inlines).
# tools/stack_depth.py and tools/ram_budget.py do the sums; tools/target_memory_doc.py puts the
# figures into docs/porting.md section 7 (--write-doc) or checks that they are there
# (--check-doc, CI).
# usage: tools/check_target_memory.sh [--write-doc | --check-doc] [OUTDIR]
#        (non-zero exit if anything does not fit, or the doc differs with --check-doc)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
doc_mode=
case "${1:-}" in
  --write-doc | --check-doc) doc_mode=$1; shift ;;
esac
out=${1:-$(mktemp -d)}
mkdir -p "$out" && out=$(cd "$out" && pwd)   # the compiles run inside it
cc=${ARM_CC:-arm-none-eabi-gcc}
command -v "$cc" >/dev/null || { echo "check_target_memory: $cc not found" >&2; exit 1; }
mapfile -t sources < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_C_SOURCES)
mapfile -t includes < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_INCLUDE_DIRS)
stack_words=$(sed -n 's/.*--stack_size=\(0x[0-9A-Fa-f]*\).*/\1/p' "$here/cmake/ti-c2000-toolchain.cmake")
[ -n "$stack_words" ] || { echo "check_target_memory: no --stack_size in the toolchain file" >&2; exit 1; }
linker="$here/firmware/f28335/F28335_flash.cmd"

compile() { # dir, extra flags...
  local dir=$1 src
  shift
  mkdir -p "$dir"
  for src in "${sources[@]}" tools/ti_link_proxy/ti_link_stubs.c; do
    (cd "$dir" && "$cc" "${flags[@]}" "$@" -c "$here/$src" -o "$dir/$(basename "$src" .c).o")
  done
}

for arith in float fixed; do
  dir="$out/$arith"
  flags=(-std=c99 -ffreestanding -mcpu=cortex-m4 -mthumb -O2 -DF28335_LINK_PROXY=1
         --param=min-pagesize=0)
  # The fixed (Q24) image leaves the MPTC-49/13 search in flash (F28335_flash.cmd, the
  # SIXPHASE_FW_Q24 branch; docs/porting.md section 7): the linker's define and what it moves.
  # Both leave the open-phase step in flash (it runs only with an isolated leg; in RAM it would
  # take L0..L3 to 93 %), and what runs once when a leg is isolated or restored; and the
  # commissioning, which runs in the interrupt instead of the control step: its entry points
  # from the period, and what only they reach (docs/porting.md section 7).
  link=()
  from_flash=ctl_postfault_step,drive_open_phase_faults,drive_isolate,hal_pwm_restore_legs
  from_flash+=,drive_commission_begin,drive_commission_period,drive_commission_angle
  from_flash+=,drive_phase_verify_start,drive_phase_verify_period,comm_abort
  # and a fault's latching, once in the period that latches it, with the writing of its record;
  # a clear (in FAULT, outputs off); the protection's quiet phases (with a leg isolated)
  from_flash+=,drive_latch_fault,drive_enter_fault,drive_report_overrun,record,ctl_protect_raise
  from_flash+=,ctl_protect_clear,ctl_protect_quiet
  if [ $arith = float ]; then
    flags+=(-DCTL_MATH_FLOAT=1)
  else
    flags+=(-DCTL_MATH_FLOAT=0)
    link=(--define SIXPHASE_FW_Q24=1)
    from_flash=ctl_mptc_select,$from_flash
  fi
  for inc in "${includes[@]}"; do flags+=(-I "$here/$inc"); done
  compile "$dir/o2" -ffunction-sections -fdata-sections -fcallgraph-info=su
  compile "$dir/noinline" -fno-inline -fcallgraph-info
  rm "$dir/noinline/ti_link_stubs.ci" # the stand-ins of cl2000's intrinsics: no code of the image
  echo "== $arith build"
  python3 "$here/tools/stack_depth.py" --background main --isr fw_adc_isr \
    --stack-words "$((stack_words))" --summary "$dir/stack.json" "$dir"/o2/*.ci
  python3 "$here/tools/ram_budget.py" --linker "$linker" "${link[@]}" --objects "$dir/o2" \
    --callgraph "$dir/noinline" --from-flash "$from_flash" --summary "$dir/ram.json"
done
if [ -n "$doc_mode" ]; then
  python3 "$here/tools/target_memory_doc.py" "$doc_mode" "$here/docs/porting.md" \
    --stack-words "$((stack_words))" --float "$out/float" --fixed "$out/fixed"
fi
