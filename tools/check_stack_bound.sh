#!/usr/bin/env bash
# An upper bound of the F28335 image's stack, checked without TI's compiler (issue 22): for the
# float (CTL_MATH_FLOAT=1) and the Q24 (CTL_MATH_FLOAT=0) image, the deepest background path
# from main plus the control interrupt (fw_adc_isr) nested at its deepest point plus the
# interrupt context must leave at least 20 % of the stack the TI link reserves (--stack_size in
# cmake/ti-c2000-toolchain.cmake). The target's C sources (cmake/sources.cmake, target code
# paths as in the host link check) are compiled for three register-poor proxies - Cortex-M0
# (the call graph, -fcallgraph-info=su), AVR (16-bit int; -fstack-usage) and i386 (every
# argument on the stack; -fstack-usage) - each at -O2 and at -O2 -fno-inline (cl2000 may
# inline either way); tools/stack_bound.py takes each function's largest frame over the
# proxies, converts it to C28x words by its documented rule, adds the allowances (return
# address and saved registers per call, run-time library helpers, ADC_cal, interrupt context)
# and prints the bound of the worse build.
# usage: tools/check_stack_bound.sh OUTDIR
#        writes OUTDIR/{float,fixed}/stack_bound.json; non-zero exit if an image leaves less
#        than 20 % of the stack (or the bound cannot be made: recursion, an unresolved
#        indirect call, an unknown routine)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
[ $# -eq 1 ] || { echo "usage: tools/check_stack_bound.sh OUTDIR" >&2; exit 2; }
out=$1
mkdir -p "$out" && out=$(cd "$out" && pwd) # the compiles run inside it
arm_cc=${ARM_CC:-arm-none-eabi-gcc}
avr_cc=${AVR_CC:-avr-gcc}
x86_cc=${X86_CC:-gcc}
for cc in "$arm_cc" "$avr_cc" "$x86_cc"; do
  command -v "$cc" >/dev/null || { echo "check_stack_bound: $cc not found" >&2; exit 1; }
done
mapfile -t sources < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_C_SOURCES)
mapfile -t includes < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_INCLUDE_DIRS)
sources+=(tools/ti_link_proxy/ti_link_stubs.c) # cl2000's intrinsics as tiny functions: counted
stack_words=$(sed -n 's/.*--stack_size=\(0x[0-9A-Fa-f]*\).*/\1/p' "$here/cmake/ti-c2000-toolchain.cmake")
[ -n "$stack_words" ] || { echo "check_stack_bound: no --stack_size in the toolchain file" >&2; exit 1; }
bool_flags=$(python3 -c "import sys; sys.path.insert(0, '$here/tools'); import stack_bound; print(stack_bound.BOOL_FLAGS)")

# Every proxy compiles with these (bool as the C28x's 16 bits: tools/stack_bound.py).
export COMMON_FLAGS="-std=c99 -ffreestanding -O2 -DF28335_LINK_PROXY=1 $bool_flags"
for inc in "${includes[@]}"; do COMMON_FLAGS+=" -I $here/$inc"; done
export M0_CC="$arm_cc -mcpu=cortex-m0 -mthumb --param=min-pagesize=0 -fcallgraph-info=su"
export AVR_CC="$avr_cc -mmcu=atmega1284p -fstack-usage"
export X86_CC="$x86_cc -m32 -mpreferred-stack-boundary=2 -maccumulate-outgoing-args --param=min-pagesize=0 -fstack-usage"

# One compile per job: DIR PROXY MATH INLINE SOURCE, two at a time.
compile_one() {
  local dir=$1 proxy=$2 math=$3 inline=$4 src=$5 cc
  case $proxy in
    m0) cc=$M0_CC ;;
    avr) cc=$AVR_CC ;;
    x86) cc=$X86_CC ;;
  esac
  [ "$inline" = noinline ] && cc+=" -fno-inline"
  # shellcheck disable=SC2086 # the flag strings are word lists
  (cd "$dir" && $cc $COMMON_FLAGS -DCTL_MATH_FLOAT="$math" -c "$src" -o "$(basename "$src" .c).o")
}
export -f compile_one
for arith in float fixed; do
  math=1
  [ $arith = fixed ] && math=0
  for build in o2 noinline; do
    for proxy in m0 avr x86; do
      dir="$out/$arith/$build/$proxy"
      rm -rf "$dir" && mkdir -p "$dir"
      for src in "${sources[@]}"; do
        echo "$dir $proxy $math $build $here/$src"
      done
    done
  done
done | xargs -P 2 -L 1 bash -c 'compile_one "$@"' _

status=0
for arith in float fixed; do
  echo "== $arith image"
  python3 "$here/tools/stack_bound.py" --background main --isr fw_adc_isr \
    --stack-words "$((stack_words))" --summary "$out/$arith/stack_bound.json" \
    "$out/$arith/o2" "$out/$arith/noinline" || status=1
done
exit $status
