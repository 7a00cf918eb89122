#!/usr/bin/env bash
# Memory of the F28335 image, checked without TI's compiler (CI runs this), for both builds:
#   - stack: the deepest background path plus a nested control interrupt must fit the stack
#     the TI link reserves (--stack_size in cmake/ti-c2000-toolchain.cmake), with margin;
#   - the image (tools/image_check.py, a model of TI's linker applied to the proxy build's
#     sections): the boot path runs where it is loaded, the control period's code, tables and
#     jump tables run from RAM and nothing else does, every memory range holds its sections.
# Compiles exactly the target's C sources (cmake/sources.cmake, target code paths as in the
# host link check) with arm-none-eabi-gcc, a 32-bit proxy for cl2000, three times per build:
# Cortex-M4 -O2 with one section per function, the sources' RAM placement
# (SIXPHASE_PLACEMENT_PROXY) and -fcallgraph-info=su (sizes, stack frames); Cortex-M4 -O2
# -fno-inline (the complete call graph of the period, whatever cl2000 inlines); and Cortex-M0
# -O2 -fno-inline (no divide instruction and no FPU: every division and 64-bit operation is a
# library call, as on the C28x, so the run-time library members the image needs show).
# tools/check_stack_bound.sh bounds the stack (register-poor proxies, its own builds);
# tools/image_check.py does the image's sums; tools/target_memory_doc.py puts the
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
  # afresh: objects and call graphs of a file no longer in the source list must not linger
  rm -rf "$dir" && mkdir -p "$dir"
  for src in "${sources[@]}" tools/ti_link_proxy/ti_link_stubs.c; do
    (cd "$dir" && "$cc" "${flags[@]}" "$@" -c "$here/$src" -o "$dir/$(basename "$src" .c).o")
  done
}

for arith in float fixed; do
  dir="$out/$arith"
  flags=(-std=c99 -ffreestanding -mthumb -O2 -DF28335_LINK_PROXY=1 --param=min-pagesize=0)
  # The Q24 link's define (F28335_flash.cmd, SIXPHASE_FW_Q24); image_check.py reads what runs
  # from flash on purpose from tools/flash_on_purpose.txt, the one list.
  link=()
  if [ $arith = float ]; then
    flags+=(-DCTL_MATH_FLOAT=1)
  else
    flags+=(-DCTL_MATH_FLOAT=0)
    link=(--define SIXPHASE_FW_Q24=1)
  fi
  for inc in "${includes[@]}"; do flags+=(-I "$here/$inc"); done
  compile "$dir/o2" -mcpu=cortex-m4 -ffunction-sections -fdata-sections -fcallgraph-info=su \
    -DSIXPHASE_PLACEMENT_PROXY=1
  compile "$dir/noinline" -mcpu=cortex-m4 -fno-inline -fcallgraph-info
  compile "$dir/m0" -mcpu=cortex-m0 -fno-inline -fcallgraph-info
  # the stand-ins of cl2000's intrinsics: no code of the image
  rm "$dir/noinline/ti_link_stubs.ci" "$dir/m0/ti_link_stubs.ci" "$dir/o2/ti_link_stubs.o"
  echo "== $arith build"
  python3 "$here/tools/image_check.py" --linker "$linker" "${link[@]}" --objects "$dir/o2" \
    --callgraph "$dir/m0" --asm "$here/firmware/f28335/codestart.asm" \
    --stack-words "$((stack_words))" --from-flash-file "$here/tools/flash_on_purpose.txt" \
    --summary "$dir/ram.json"
done
"$here/tools/check_stack_bound.sh" "$out" # -> $out/{float,fixed}/stack_bound.json; 20 % left
if [ -n "$doc_mode" ]; then
  python3 "$here/tools/target_memory_doc.py" "$doc_mode" "$here/docs/porting.md" \
    --stack-words "$((stack_words))" --float "$out/float" --fixed "$out/fixed"
fi
