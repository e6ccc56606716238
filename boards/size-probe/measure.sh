#!/usr/bin/env bash
# Flash cost of each arealight model family: builds the size probe once per family and target
# and prints a markdown table of .text bytes above the empty probe (the runtime alone).
# Usage: boards/size-probe/measure.sh [out.md]
set -euo pipefail
# The output path as given, relative to the caller's directory (before the cd below).
out=${1:-/dev/stdout}
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
cd "$(dirname "$0")"
unset CARGO_TARGET_DIR
rustup component add llvm-tools >/dev/null 2>&1 || true
size_tool="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin/llvm-size"
families=(hemisphere cap polygon phong sh9 line moments shaping)
text_of() { # target features
  local target=$1 features=$2
  cargo build -q --release --target "$target" --no-default-features ${features:+--features "$features"}
  "$size_tool" -A "target/$target/release/size-probe" | awk '$1 == ".text" { print $2 }'
}
{
  echo "| feature set | thumbv7em (M4F, f32) .text | thumbv6m (M0, f32 soft-float) .text | thumbv6m (M0, Fixed22) .text |"
  echo "|---|---|---|---|"
  b7=$(text_of thumbv7em-none-eabihf "")
  b6=$(text_of thumbv6m-none-eabi "")
  b6f=$(text_of thumbv6m-none-eabi "fixed")
  echo "| (runtime only: the baseline subtracted below) | $b7 | $b6 | $b6f |"
  all7=0; all6=0; all6f=0
  for f in "${families[@]}"; do
    t7=$(( $(text_of thumbv7em-none-eabihf "$f") - b7 ))
    t6=$(( $(text_of thumbv6m-none-eabi "$f") - b6 ))
    t6f=$(( $(text_of thumbv6m-none-eabi "$f,fixed") - b6f ))
    echo "| \`$f\` alone | $t7 | $t6 | $t6f |"
  done
  all=$(IFS=,; echo "${families[*]}")
  echo "| all families | $(( $(text_of thumbv7em-none-eabihf "$all") - b7 )) | $(( $(text_of thumbv6m-none-eabi "$all") - b6 )) | $(( $(text_of thumbv6m-none-eabi "$all,fixed") - b6f )) |"
} > "$out"
