#!/usr/bin/env bash
# Compile the control core as freestanding C99 for a 32-bit Arm core, with only the
# compiler's own freestanding headers on the include path (no libc headers at all), in both
# arithmetic builds, and report the object sizes. Proves control/ needs no hosted library.
# usage: tools/check_freestanding.sh [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$(mktemp -d)}
cc=${ARM_CC:-arm-none-eabi-gcc}
command -v "$cc" >/dev/null || { echo "check_freestanding: $cc not found" >&2; exit 1; }
gcc_inc=$("$cc" -print-file-name=include)
flags=(-std=c99 -ffreestanding -nostdinc -isystem "$gcc_inc" -mcpu=cortex-m4 -mthumb -O2
       -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wdouble-promotion -Wshadow
       -Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-qual -Wvla -Werror
       -I "$here/control/include" -I "$here/control/platform")
mkdir -p "$out"
for arith in 0 1; do
  objs=()
  for src in "$here"/control/src/*.c; do
    obj="$out/$(basename "$src" .c).arith$arith.o"
    "$cc" "${flags[@]}" -DCTL_MATH_FLOAT=$arith -c "$src" -o "$obj"
    objs+=("$obj")
  done
  name=$([ $arith = 0 ] && echo fixed || echo float)
  echo "control core ($name), freestanding $cc:"
  arm-none-eabi-size -t "${objs[@]}" | tail -n 1 | awk '{printf "  text %s  data %s  bss %s bytes\n", $1, $2, $3}'
  # Link the objects into one relocatable object: what is still undefined comes from outside.
  # gcc itself may emit memcpy/memset for struct copies (its documented freestanding contract);
  # anything else, or the compiler's runtime helpers aside, would be a libc dependency.
  "$cc" -nostdlib -r -o "$out/control_$name.o" "${objs[@]}"
  undefined=$(arm-none-eabi-nm -u "$out/control_$name.o" | awk '{print $NF}' \
    | grep -v -E '^(__aeabi_|__gnu_|memcpy$|memset$|memmove$|memcmp$)' | sort -u || true)
  if [ -n "$undefined" ]; then
    echo "check_freestanding: control core ($name) references external symbols: $undefined" >&2
    exit 1
  fi
done
echo "check_freestanding: ok"
