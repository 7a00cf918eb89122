#!/usr/bin/env bash
# The post-fault control step's cost (docs/design.md): host instructions per step under
# callgrind, for every controller and arithmetic, healthy against phase C open, on the periods of
# a ride-through run after the isolation. The F28335 time is priced by the benchmark's cost model
# (tools/bench/c28x_cost.py, docs/performance.md), not here.
# usage: tools/bench/postfault_cost.sh BUILD_DIR   (e.g. build/host)
set -euo pipefail
b=${1:?usage: postfault_cost.sh BUILD_DIR}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$b/host_sim/sixphase-sim" run --controller ddc --scenario fault-open-phase --ride-through \
  --load 3.5 --quiet --no-fine --out "$work/run"
printf "| controller | arithmetic | open phase | instructions / step |\n|---|---|---|---|\n"
for ctl in 0 1 2; do
  for arith in fixed float; do
    for leg in -1 2; do
      steps=$("$b/tools/bench/postfault-cost-$arith" "$work/run/trace.csv" $ctl $leg | awk '{print $2}')
      ir=$(valgrind --tool=callgrind --toggle-collect=ctl_step --callgrind-out-file="$work/cg" \
             "$b/tools/bench/postfault-cost-$arith" "$work/run/trace.csv" $ctl $leg 2>&1 |
           sed -n 's/.*Collected : //p')
      name=(DDC MPTC-49 MPTC-13)
      printf "| %s | %s | %s | %d |\n" "${name[$ctl]}" $arith \
        "$([ $leg = -1 ] && echo none || echo C)" $((ir / steps))
    done
  done
done
