#!/bin/sh
# rustc wrapper of the measured board workspaces (their .cargo/config.toml set
# `build.rustc-wrapper` to this file), so that a clone of the repository at any path builds
# the same bytes. Cargo calls it as `rustc-remap.sh <rustc> <args...>`.
#
# Two things tie a board's firmware to the checkout's path, and both move the instruction and
# cycle counts the README tables report (by a fraction of a percent between two clones):
#
# 1. Panic locations embed each source file's path (`/home/me/arealight/src/polygon.rs`,
#    `$CARGO_HOME/registry/src/.../lib.rs`): their length moves the data. Stable rustc's
#    `--remap-path-prefix` fixes that, but its FROM is an absolute path, which a config file
#    cannot compute: this wrapper adds it, for the repository and for Cargo's home.
# 2. The crates outside the board's own workspace (arealight at ../.., boards/demo-scene) get
#    a `-C metadata` hash from Cargo that includes their absolute path, and so does every crate
#    depending on them. The hash seeds the symbol hashes, which order the functions in the LTO
#    module, which changes code generation (measured: 40 bytes of one raster function). The
#    wrapper replaces it with a hash of the same compilation's path-free arguments (crate
#    name, version, source file relative to the repository or Cargo's home, features, target,
#    code generation flags); Cargo's own file names (`-C extra-filename`) are kept.
rustc=$1
shift
case " $* " in
*" --crate-name "*) ;;
*) exec "$rustc" "$@" ;; # version and target queries: nothing to remap
esac
here=$(cd "$(dirname "$0")/.." && pwd -L)
root=$(cd "$(dirname "$0")/.." && pwd -P)
home=${CARGO_HOME:-$HOME/.cargo}
[ -d "$home" ] && home=$(cd "$home" && pwd -P)

# The path-free key of this compilation: every argument but the ones naming files of the
# target directory (whose names carry Cargo's path-dependent hashes), with the two prefixes
# replaced.
key="$CARGO_PKG_NAME $CARGO_PKG_VERSION"
n=$#
skip=0
codegen=0
for a in "$@"; do
  if [ "$skip" = 1 ]; then
    skip=0
    set -- "$@" "$a"
    continue
  fi
  if [ "$codegen" = 1 ]; then
    codegen=0
    case "$a" in
    metadata=*) set -- "$@" "metadata=@META@" ;;
    extra-filename=*) set -- "$@" "$a" ;;
    *) key="$key
-C $a"; set -- "$@" "$a" ;;
    esac
    continue
  fi
  case "$a" in
  -C) codegen=1 ;;
  -Cmetadata=*) a="-Cmetadata=@META@" ;;
  -Cextra-filename=*) ;;
  --extern | -L | --out-dir) skip=1 ;;
  --extern=* | -L* | --out-dir=* | --diagnostic-width=*) ;;
  *) key="$key
$a" ;;
  esac
  set -- "$@" "$a"
done
shift "$n"
meta=$(printf '%s\n' "$key" | awk -v r="$root" -v h="$here" -v c="$home" '
  function swap(s, from, to,   i) {
    while (from != "" && (i = index(s, from)) > 0) s = substr(s, 1, i - 1) to substr(s, i + length(from))
    return s
  }
  { print swap(swap(swap($0, r, "/arealight"), h, "/arealight"), c, "/cargo-home") }' | cksum | tr ' ' '-')

# Rebuild the argument list with the new metadata and the remapped prefixes. When several
# prefixes match, rustc applies the last one given: the repository's.
n=$#
for a in "$@"; do
  case "$a" in
  *@META@) a="${a%@META@}al$meta" ;;
  esac
  set -- "$@" "$a"
done
shift "$n"
exec "$rustc" "$@" \
  "--remap-path-prefix=$home=/cargo-home" \
  "--remap-path-prefix=$here=/arealight" \
  "--remap-path-prefix=$root=/arealight"
