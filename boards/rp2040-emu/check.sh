#!/usr/bin/env bash
# Runs both RP2040 firmwares (boards/rp2040-st7789) in the rp2040js emulator for N frames
# (default 2), checks every frame byte for byte against the host render of the same scene
# (boards/demo-scene's reference_frames example), and reports cycles per frame.
#
#   boards/rp2040-emu/check.sh [N]
#
# Output under the repository's target/rp2040-emu/: reference/ (host frames), lit_scene/ and
# lit_scene_dual_core/ (emulated frames, .rgb565 and .png), the run logs, and frames.md (the
# cycles table, for README.md), frames.csv (the same frames, per stage, for `host-sim budget
# --scene --check`), and calibration.csv (the `calibrate` binary's unit costs, for `host-sim
# budget --calibrate`), and scenes.csv (the `scene_file` binary's frame of each scene file of
# demo_scene::scenes, for `host-sim budget --scene host-sim/scenes/NAME.toml --check`). Exits
# non-zero if a run fails or a frame differs.
set -euo pipefail

frames=${1:-2}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$root/target/rp2040-emu
firmware=$root/boards/rp2040-st7789
elf_dir=$firmware/target/emu/thumbv6m-none-eabi/release
mkdir -p "$out"

if [ ! -d "$here/node_modules" ]; then
  echo "== npm ci"
  (cd "$here" && npm ci --no-audit --no-fund)
fi

echo "== firmware (--features emulator, target dir boards/rp2040-st7789/target/emu)"
(cd "$firmware" && env -u CARGO_TARGET_DIR cargo build --release --features emulator --target-dir target/emu)

echo "== host reference frames 0..$((frames - 1))"
rm -rf "$out/reference"
(cd "$root/boards/demo-scene" &&
  env -u CARGO_TARGET_DIR cargo run --quiet --release --example reference_frames \
    --target-dir "$out/host" -- "$out/reference" "$frames" >/dev/null)

status=0
logs=()
for bin in lit_scene lit_scene_dual_core; do
  flags=()
  [ "$bin" = lit_scene_dual_core ] && flags=(--dual)
  echo "== $bin: $frames frames in the emulator"
  rm -rf "${out:?}/$bin"
  set +e
  node "$here/run.mjs" --elf "$elf_dir/$bin" --frames "$frames" "${flags[@]}" --dump-frames "$out/$bin" \
    >"$out/$bin.log" 2>&1
  run_status=$?
  set -e
  grep -E '^(\[frame\]|\[defmt\]|\[emulator\]|error:)' "$out/$bin.log" || true
  if [ $run_status -ne 0 ]; then
    echo "$bin: the emulator run failed (exit $run_status; log: $out/$bin.log)"
    status=1
  fi
  logs+=("$out/$bin.log")
  echo "== $bin: frames against the host render"
  if ! node "$here/report.mjs" compare "$out/reference" "$out/$bin" "$frames"; then
    echo "$bin: frames differ from the host render"
    status=1
  fi
done

echo "== cycles per frame ($out/frames.md, $out/frames.csv)"
if node "$here/report.mjs" table "${logs[@]}" >"$out/frames.md" &&
  node "$here/report.mjs" csv "${logs[@]}" >"$out/frames.csv"; then
  cat "$out/frames.md"
else
  status=1
fi

echo "== calibrate: unit costs for host-sim budget --scene ($out/calibration.csv)"
set +e
node "$here/run.mjs" --elf "$elf_dir/calibrate" --until "calibration done" >"$out/calibrate.log" 2>&1
run_status=$?
set -e
grep -E '^(\[defmt\]|error:)' "$out/calibrate.log" || true
if [ $run_status -ne 0 ] || ! node "$here/report.mjs" costs "$out/calibrate.log" >"$out/calibration.csv"; then
  echo "calibrate: the emulator run failed (log: $out/calibrate.log)"
  status=1
fi
echo "== scene_file: the scene files of host-sim/scenes/ ($out/scenes.csv; --features scene-file, the same target dir)"
(cd "$firmware" && env -u CARGO_TARGET_DIR cargo build --release --features emulator,scene-file --bin scene_file --target-dir target/emu)
set +e
node "$here/run.mjs" --elf "$elf_dir/scene_file" --until "scene files done" \
  >"$out/scene_file.log" 2>&1
run_status=$?
set -e
grep -E '^(\[defmt\]|error:)' "$out/scene_file.log" || true
if [ $run_status -ne 0 ] || grep -q ' ERROR ' "$out/scene_file.log" ||
  ! node "$here/report.mjs" csv "$out/scene_file.log" >"$out/scenes.csv" ||
  [ "$(wc -l <"$out/scenes.csv")" -lt 3 ]; then
  echo "scene_file: the emulator run failed or logged no scene frames (log: $out/scene_file.log)"
  status=1
fi
if [ $status -eq 0 ]; then echo "rp2040-emu: all frames identical to the host render"; fi
exit $status
