#!/usr/bin/env bash
# Installs the Debian packages the build, the tests and the report need (idempotent).
# Runs apt-get directly as root, through sudo otherwise. llvm: llvm-profdata and llvm-cov
# (tools/fuzz_coverage.sh).
set -euo pipefail
packages=(cmake gcc make libcmocka-dev clang-format cppcheck gcc-arm-none-eabi clang libclang-rt-14-dev llvm
          libnewlib-arm-none-eabi python3 python3-matplotlib python3-numpy valgrind
          gcc-avr avr-libc binutils-avr simavr libsimavr-dev qemu-system-arm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
