#!/usr/bin/env bash
# Memory of the F28335 image, checked without TI's compiler (CI runs this):
#   - stack: the deepest background path plus a nested control interrupt must fit the stack
#     the TI link reserves (--stack_size in cmake/ti-c2000-toolchain.cmake), with margin;
#   - RAM: the per-period path the flash linker file copies to L0..L3 (ramfuncs) and all
#     static data (.ebss in L4..L7) must fit their blocks, with margin.
# Compiles exactly the target's C sources (cmake/sources.cmake, target code paths as in the
# host link check) with arm-none-eabi-gcc -O2 -fcallgraph-info=su, a 32-bit proxy for cl2000,
# in the float build (the F28335 default) and the fixed build. tools/stack_depth.py and
# tools/ram_budget.py do the sums; their output goes into docs/porting.md section 7. The RAM
# budget is enforced for the float build; the fixed build's is reported (its inlined 64-bit
# arithmetic is far larger on the proxy than it may be on the C28x; see porting.md).
# usage: tools/check_target_memory.sh [OUTDIR]   (non-zero exit if anything does not fit)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$(mktemp -d)}
mkdir -p "$out" && out=$(cd "$out" && pwd)   # the compiles run inside it
cc=${ARM_CC:-arm-none-eabi-gcc}
command -v "$cc" >/dev/null || { echo "check_target_memory: $cc not found" >&2; exit 1; }
mapfile -t sources < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_C_SOURCES)
mapfile -t includes < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_INCLUDE_DIRS)
stack_words=$(sed -n 's/.*--stack_size=\(0x[0-9A-Fa-f]*\).*/\1/p' "$here/cmake/ti-c2000-toolchain.cmake")
[ -n "$stack_words" ] || { echo "check_target_memory: no --stack_size in the toolchain file" >&2; exit 1; }
for arith in float fixed; do
  dir="$out/$arith"
  mkdir -p "$dir"
  flags=(-std=c99 -ffreestanding -mcpu=cortex-m4 -mthumb -O2 -fcallgraph-info=su
         -DF28335_LINK_PROXY=1 --param=min-pagesize=0)
  [ $arith = float ] && flags+=(-DCTL_MATH_FLOAT=1) || flags+=(-DCTL_MATH_FLOAT=0)
  for inc in "${includes[@]}"; do flags+=(-I "$here/$inc"); done
  objs=()
  for src in "${sources[@]}" tools/ti_link_proxy/ti_link_stubs.c; do
    obj="$dir/$(basename "$src" .c).o"
    (cd "$dir" && "$cc" "${flags[@]}" -c "$here/$src" -o "$obj")
    objs+=("$obj")
  done
  echo "== $arith build"
  # Indirect calls (the serial command table, the stage hook) follow the sources'
  # `indirect-call:` notes; one without a note fails.
  python3 "$here/tools/stack_depth.py" --background main --isr fw_adc_isr \
    --stack-words "$((stack_words))" "${objs[@]/%.o/.ci}"
  budget=(--linker "$here/firmware/f28335/F28335_flash.cmd" --size arm-none-eabi-size)
  [ $arith = fixed ] && budget+=(--report-only)
  python3 "$here/tools/ram_budget.py" "${budget[@]}" "${objs[@]}"
done
