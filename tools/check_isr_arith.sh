#!/usr/bin/env bash
# No 64-bit integer or double arithmetic on the per-period path of the F28335 image (issue 10,
# item 8): on the C28x those are run-time-library calls of hundreds of cycles inside the 80 us
# control ISR. Compiles the target's C sources (cmake/sources.cmake, the float build, the
# F28335 default) for a Cortex-M0, which has no 64-bit multiply or divide instruction, so every
# such operation becomes a helper call in gcc's call graph; tools/isr_arith.py walks the graph
# from the control ISR (fw_adc_isr) and fails on __aeabi_l* / __aeabi_ul* (64-bit integer) and
# __aeabi_d* (double) helpers. 32-bit division and float helpers are allowed (the C28x has an
# FPU and a 32-bit division sequence).
# usage: tools/check_isr_arith.sh [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$(mktemp -d)}
mkdir -p "$out" && out=$(cd "$out" && pwd)
cc=${ARM_CC:-arm-none-eabi-gcc}
command -v "$cc" >/dev/null || { echo "check_isr_arith: $cc not found" >&2; exit 1; }
mapfile -t sources < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_C_SOURCES)
mapfile -t includes < <(cmake -P "$here/tools/print_sources.cmake" SIXPHASE_TARGET_INCLUDE_DIRS)
flags=(-std=c99 -ffreestanding -mcpu=cortex-m0 -mthumb -O2 -fcallgraph-info
       -DF28335_LINK_PROXY=1 -DCTL_MATH_FLOAT=1 --param=min-pagesize=0)
for inc in "${includes[@]}"; do flags+=(-I "$here/$inc"); done
rm -f "$out"/*.ci "$out"/*.o # a file no longer in the source list leaves no call graph behind
for src in "${sources[@]}" tools/ti_link_proxy/ti_link_stubs.c; do
  (cd "$out" && "$cc" "${flags[@]}" -c "$here/$src" -o "$out/$(basename "$src" .c).o")
done
python3 "$here/tools/isr_arith.py" --root fw_adc_isr \
  --forbid '^__aeabi_(l|ul|d)|di3$|df' "$out"/*.ci
