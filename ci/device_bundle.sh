#!/usr/bin/env bash
# Packs what ci/device.sh runs into one file, for a GPU machine that cannot build it: one with
# nvcc and a driver but no Debian packages and no network (the lent machines of this project's
# sessions). Run it here, on a machine where ci/setup.sh built the CUDA backend; carry the file
# to the GPU machine's checkout and run `bash ci/device.sh` there, which finds and uses it.
#
# The file holds the device test programs and `shadowcts` (stripped), every shared library they
# load except the driver's libcuda (their ldd closure, glibc and its dynamic loader included, so
# they run whatever the other machine's C library is), and the model fixtures' files.
#   SHADOWCTS_BUILD_DIR      build folder with the CUDA backend (default: build)
#   SHADOWCTS_DEVICE_BUNDLE  the file to write (default: .device-bundle.tar.xz, git-ignored)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${SHADOWCTS_BUILD_DIR:-build}"
bundle="${SHADOWCTS_DEVICE_BUNDLE:-.device-bundle.tar.xz}"
source ci/device_programs.sh
models="${SHADOWCTS_ASSIMP_MODELS:-/usr/share/assimp/models}"

configured="$(cmake -S . -B "$build" 2>&1)" || { echo "$configured" >&2; exit 1; }
if ! grep -q "CUDA backend is built" <<<"$configured"; then
  echo "device_bundle: $build builds no CUDA backend (no nvcc here? ci/setup.sh on a machine with nvcc)" >&2
  exit 2
fi
targets=()
for p in "${device_programs[@]}"; do targets+=(--target "$(basename "$p")"); done
cmake --build "$build" -j "$(nproc)" "${targets[@]}"

stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
root="$stage/shadowcts-device"
mkdir -p "$root/bin" "$root/lib" "$root/models"
for p in "${device_programs[@]}"; do
  cp "$build/$p" "$root/bin/"
  strip "$root/bin/$(basename "$p")"
done
# Shared libraries: the closure ldd reports, less the driver (it must be the machine's own).
declare -A libraries=()
for p in "${device_programs[@]}"; do
  while read -r path; do libraries["$path"]=1; done < <(ldd "$build/$p" | awk '$3 ~ /^\// { print $3 }
    $1 ~ /^\/.*ld-linux/ { print $1 }')
done
for path in "${!libraries[@]}"; do
  case "$(basename "$path")" in libcuda.so*) continue ;; esac
  cp -L "$path" "$root/lib/"
done
# The driver's libcuda needs these parts of glibc, which the programs themselves may not: carry
# them from the same glibc, so the system's copies never mix with the carried libc.
libc_dir="$(dirname "$(ldd "$build/shadowcts" | awk '$1 == "libc.so.6" { print $3 }')")"
for part in libdl.so.2 libpthread.so.0 librt.so.1 libm.so.6 libresolv.so.2; do
  [ -e "$libc_dir/$part" ] && cp -L "$libc_dir/$part" "$root/lib/"
done
ls "$root"/lib/ld-linux-x86-64.so.* >/dev/null 2>&1 ||
  { echo "device_bundle: ldd named no dynamic loader" >&2; exit 1; }
# The model fixtures' files, in assimp-testmodels' layout (SHADOWCTS_ASSIMP_MODELS).
"$build/shadowcts" list | awk '$2 == "assimp-testmodels" { print $3 }' | while read -r model; do
  mkdir -p "$root/models/$(dirname "$model")"
  cp "$models/$model" "$root/models/$model"
done
git rev-parse HEAD > "$root/commit"
git status --porcelain --untracked-files=no | grep -q . && echo "(with uncommitted changes)" >> "$root/commit"

tar -C "$stage" -cf - shadowcts-device | xz -T0 -6 > "$bundle.partial"
mv "$bundle.partial" "$bundle"
echo "device_bundle: wrote $bundle ($(du -h "$bundle" | cut -f1), commit $(head -n 1 "$root/commit"))"
