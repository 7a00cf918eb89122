#!/usr/bin/env bash
# Executable portability proxy for the C28x (16-bit int, 32-bit double): runs the SAME control
# core on an 8-bit AVR (avr-gcc: 16-bit int, 32-bit double) under simavr and on the host, over
# the same input records built from simulator traces, and compares the outputs.
#   fixed build (CTL_MATH_FLOAT=0): byte-identical outputs, else the first differing field
#   float build (CTL_MATH_FLOAT=1): identical commands; diagnostic differences are reported
# The core is compiled for the AVR and the compared host build with -D__TMS320C2000__, so the
# code paths under test are the ones TI's cl2000 compiles (portable saturation and top-bit
# search, out-of-line barrier) rather than the gcc builtins; a second host build with the gcc
# paths (what the host tools and tests run) is compared with it by the same rule.
# usage: tools/avr_proxy/run.sh [--out DIR] [--scale X] [--gcc-paths] [--inject-bug]
#   --gcc-paths    compile the AVR side with the gcc builtin paths instead
#   --out DIR      work directory (default build/avr-proxy)
#   --scale X      input length factor (1.0: about 21,000 steps)
#   --inject-bug   teeth check: build from a scratch copy of control/ with an int-width bug
#                  (an int16 product that overflows a 16-bit int) and expect the fixed
#                  comparison to FAIL; exits 0 only if the proxy catches it
# The host-vs-AVR results also go to DIR/compare-fixed.json and compare-float.json (steps,
# identical or not, largest float diagnostic difference): docs/performance.md reports them.
# env: SIXPHASE_SIM=path to a built sixphase-sim (else it is built in DIR/host)
# Needs gcc-avr avr-libc binutils-avr simavr libsimavr-dev python3 (tools/install-deps.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
proxy="$here/tools/avr_proxy"
out="$here/build/avr-proxy"
scale=1.0
inject=0
ti_paths=(-D__TMS320C2000__)
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --scale) scale=$2; shift 2 ;;
    --inject-bug) inject=1; shift ;;
    --gcc-paths) ti_paths=(); shift ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
mcu=atmega1284p
for t in avr-gcc avr-size avr-nm gcc python3 cmake; do
  command -v "$t" >/dev/null || { echo "run.sh: $t not found (tools/install-deps.sh)" >&2; exit 2; }
done
simavr_inc=/usr/include/simavr
[ -f "$simavr_inc/sim_avr.h" ] || { echo "run.sh: simavr headers not found (libsimavr-dev)" >&2; exit 2; }
mkdir -p "$out"
t0=$(date +%s)

# The core under test: control/ itself, or a scratch copy with an injected int-width bug.
core="$here/control"
if [ "$inject" = 1 ]; then
  core="$out/control-bug"
  rm -rf "$core"
  cp -r "$here/control" "$core"
  # Fixed-point sine interpolation (ctl_qmath.c, used in every step): the exact 64-bit product
  # replaced by int16 pieces whose product fits 16 bits but, scaled by 4, only a 32-bit int.
  python3 - "$core/src/ctl_qmath.c" <<'EOF'
import sys
p = sys.argv[1]
s = open(p).read()
old = "    return y0 + (int32_t)(((int64_t)dy * frac + 0x2000) >> 14);\n"
new = ("    const int16_t d9 = (int16_t)(dy >> 9);\n"
       "    const int16_t f7 = (int16_t)(frac >> 7);\n"
       "    return y0 + (int32_t)(d9 * f7 * 4); /* INJECTED BUG: int16*int16*4 in int */\n")
if s.count(old) != 1:
    sys.exit("run.sh: the injection point in ctl_qmath.c was not found")
open(p, "w").write(s.replace(old, new))
EOF
  echo "run.sh: INJECTED an int-width bug into the scratch copy $core/src/ctl_qmath.c (control/ untouched)"
fi

# 1. Builds: AVR ELF and host replay per arithmetic, the simavr harness, the simulator.
# -Os: at -O2 the core's inlined 64-bit arithmetic no longer fits the 128 KB of flash once the
# open-phase step is in (155 KB); the host side stays at -O2.
avr_flags=(-mmcu=$mcu -std=c99 -Os -Wall -Wextra -Wpedantic -Werror -I "$core/include"
           -I "$core/platform")
host_flags=(-std=c99 -O2 -Wall -Wextra -Wpedantic -Werror -ffp-contract=off -I "$core/include"
            -I "$core/platform")
pids=()
for a in 0 1; do
  avr-gcc "${avr_flags[@]}" "${ti_paths[@]}" -DCTL_MATH_FLOAT=$a "$core"/src/*.c \
    "$proxy/replay.c" -o "$out/replay-avr-$a.elf" & pids+=($!)
  gcc "${host_flags[@]}" "${ti_paths[@]}" -DCTL_MATH_FLOAT=$a "$core"/src/*.c "$proxy/replay.c" \
    -o "$out/replay-host-$a" & pids+=($!)
  gcc "${host_flags[@]}" -DCTL_MATH_FLOAT=$a "$core"/src/*.c "$proxy/replay.c" \
    -o "$out/replay-host-gcc-$a" & pids+=($!)
done
gcc -std=gnu99 -O2 -Wall -Wextra -I "$simavr_inc" "$proxy/harness.c" -o "$out/harness" -lsimavr &
pids+=($!)
sim=${SIXPHASE_SIM:-}
if [ -z "$sim" ]; then
  sim="$out/host/host_sim/sixphase-sim"
  {
    cmake -S "$here" -B "$out/host" -DCMAKE_BUILD_TYPE=Release >"$out/cmake.log" 2>&1 &&
      cmake --build "$out/host" --target sixphase-sim -j2 >>"$out/cmake.log" 2>&1
  } || { echo "run.sh: building sixphase-sim failed, see $out/cmake.log" >&2; exit 1; } &
  pids+=($!)
fi
for p in "${pids[@]}"; do
  wait "$p" || { echo "run.sh: a build failed" >&2; exit 1; }
done

# 2. Inputs from freshly recorded traces.
python3 "$proxy/gen_inputs.py" --sim "$sim" --work "$out/traces" --scale "$scale" \
  --out-fixed "$out/input-0.bin" --out-float "$out/input-1.bin"

# 3. Run: host replays, then both AVR runs in parallel (one per core).
for a in 0 1; do
  "$out/replay-host-$a" <"$out/input-$a.bin" >"$out/host-$a.out"
  "$out/replay-host-gcc-$a" <"$out/input-$a.bin" >"$out/host-gcc-$a.out"
done
pids=()
for a in 0 1; do
  floor=$(avr-nm "$out/replay-avr-$a.elf" | awk '$3 == "_end" { print $1 }')
  floor=$(( 0x$floor & 0xFFFF ))
  "$out/harness" "$out/replay-avr-$a.elf" "$out/input-$a.bin" "$out/avr-$a.out" \
    --mcu $mcu --max-cycles 8000000000 --stack-floor "$floor" >"$out/harness-$a.log" 2>&1 &
  pids+=($!)
done
rc=0
for a in 0 1; do
  if ! wait "${pids[$a]}"; then
    echo "run.sh: the AVR run ($([ $a = 0 ] && echo fixed || echo float)) failed:" >&2
    grep -v '^Loaded' "$out/harness-$a.log" >&2 || true
    rc=1
  fi
done
[ $rc = 0 ] || exit 1

# 4. Compare and summarise.
echo "host vs AVR (${ti_paths[*]:-gcc builtin paths} on both):"
python3 "$proxy/compare.py" --arith fixed --summary "$out/compare-fixed.json" \
  "$out/host-0.out" "$out/avr-0.out" || rc=1
python3 "$proxy/compare.py" --arith float --summary "$out/compare-float.json" \
  "$out/host-1.out" "$out/avr-1.out" || rc=1
if [ ${#ti_paths[@]} -gt 0 ]; then
  echo "host, gcc builtin paths vs TI paths:"
  python3 "$proxy/compare.py" --arith fixed --quiet "$out/host-gcc-0.out" "$out/host-0.out" || rc=1
  python3 "$proxy/compare.py" --arith float --quiet "$out/host-gcc-1.out" "$out/host-1.out" || rc=1
fi
field() { sed -n "s/.*\b$2=\([0-9.]*\).*/\1/p" "$out/harness-$1.log" | head -n 1; }
echo "summary ($mcu under simavr, RAM 16384 bytes, flash 131072 bytes):"
for a in 0 1; do
  name=$([ $a = 0 ] && echo fixed || echo float)
  read -r text data bss _ < <(avr-size "$out/replay-avr-$a.elf" | tail -n 1)
  printf '  %-5s ctl_step cycles mean %s max %s (%s steps); protect_check mean %s max %s;\n' \
    "$name" "$(field $a step_cycles_mean)" "$(field $a step_cycles_max)" "$(field $a step_calls)" \
    "$(field $a protect_cycles_mean)" "$(field $a protect_cycles_max)"
  printf '        request_params mean %s max %s; flash %d B; RAM static %d B (.data %d, of it const tables), stack peak %s B, free %s B\n' \
    "$(field $a params_cycles_mean)" "$(field $a params_cycles_max)" $((text + data)) \
    $((data + bss)) "$data" "$(field $a stack_peak_bytes)" "$(field $a free_ram_bytes)"
done
echo "run.sh: $( [ $rc = 0 ] && echo PASS || echo FAIL ) in $(( $(date +%s) - t0 )) s"
if [ "$inject" = 1 ]; then
  rm -rf "$core"
  if [ $rc = 0 ]; then
    echo "run.sh: the injected int-width bug was NOT caught" >&2
    exit 1
  fi
  echo "run.sh: the injected int-width bug was caught (expected failure above); scratch copy removed"
  exit 0
fi
exit $rc
