#!/usr/bin/env bash
# Builds the libFuzzer targets, OSS-Fuzz style: honours $CC $CXX $CFLAGS $CXXFLAGS
# $LIB_FUZZING_ENGINE $OUT (and $WORK for the CMake build folder) when they are set, as the
# OSS-Fuzz / ClusterFuzzLite build containers set them; otherwise builds locally with clang-14,
# ASan + UBSan into build-fuzz/ (targets and seed corpora in build-fuzz/out).
# The project's libraries are built here too, with the same compiler and sanitizer flags (a
# separate CMake build folder with -DSHADOWCTS_FUZZ=ON), so the fuzzers see instrumented code.
#   SHADOWCTS_JOBS  parallel build jobs (default: number of cores)
#   SHADOWCTS_FUZZ_WERROR  ON: warnings are errors (fuzz/run_ci.sh sets it; default OFF)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

export CC="${CC:-clang-14}"
export CXX="${CXX:-clang++-14}"
sanitizers="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
export CFLAGS="${CFLAGS:--O1 -g -fno-omit-frame-pointer ${sanitizers} -fsanitize=fuzzer-no-link}"
export CXXFLAGS="${CXXFLAGS:-${CFLAGS}}"
LIB_FUZZING_ENGINE="${LIB_FUZZING_ENGINE:--fsanitize=fuzzer}"
OUT="${OUT:-${root}/build-fuzz/out}"
WORK="${WORK:-${root}/build-fuzz}"
jobs="${SHADOWCTS_JOBS:-$(nproc)}"
build="${WORK}/cmake"

launcher=()
# As in ci/setup.sh: a clone at another path (CI's) reuses the cache; with -g the object's
# compilation folder is then the first build's, which only a debugger would notice.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# Warnings are errors where CI asks for it (fuzz/run_ci.sh, Debian's clang 14), not by default:
# OSS-Fuzz's newer clang brings warnings of its own, which must not break its builds.
# RelWithDebInfo with empty per-type flags: the optimization level comes from $CFLAGS (as
# OSS-Fuzz wants), and NDEBUG stays undefined so assertions fire under the fuzzer.
cmake -S "${root}" -B "${build}" \
  -DCMAKE_C_COMPILER="${CC}" -DCMAKE_CXX_COMPILER="${CXX}" \
  -DCMAKE_C_FLAGS="${CFLAGS}" -DCMAKE_CXX_FLAGS="${CXXFLAGS}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS_RELWITHDEBINFO= \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO= \
  -DSHADOWCTS_FUZZ=ON -DSHADOWCTS_FUZZING_ENGINE="${LIB_FUZZING_ENGINE}" \
  -DSHADOWCTS_CUDA=OFF -DSHADOWCTS_WERROR="${SHADOWCTS_FUZZ_WERROR:-OFF}" "${launcher[@]}"
cmake --build "${build}" --target shadowcts_fuzz -j "${jobs}"

mkdir -p "${OUT}"
targets=(fuzz_gltf_loader fuzz_obj_loader fuzz_off_loader fuzz_ply_loader fuzz_stl_loader
  fuzz_case_manifest fuzz_gbuffer_exr fuzz_watertight fuzz_degenerate fuzz_differential)
# OSS-Fuzz and ClusterFuzzLite (their containers set FUZZING_ENGINE) run every program in $OUT
# that holds LLVMFuzzerTestOneInput as a libFuzzer target, with libFuzzer's flags, which the
# CI-mode programs (<target>_ci, support/ci_driver.cpp) refuse. They and reproducer_round_trip
# serve run_ci.sh only, so they stay out of that $OUT.
ci_programs=1
if [ -n "${FUZZING_ENGINE:-}" ]; then ci_programs=0; fi
for target in "${targets[@]}"; do
  cp "${build}/fuzz/${target}" "${OUT}/"
  if [ "${ci_programs}" = 1 ]; then cp "${build}/fuzz/${target}_ci" "${OUT}/"; fi
  seeds="${OUT}/${target}_seed_corpus"
  rm -rf "${seeds}"
  mkdir -p "${seeds}"
  committed="${root}/fuzz/corpus/${target#fuzz_}"
  if [ -d "${committed}" ]; then cp "${committed}"/* "${seeds}/"; fi
  if [ -f "${root}/fuzz/options/${target}.options" ]; then
    cp "${root}/fuzz/options/${target}.options" "${OUT}/"
  fi
done
if [ "${ci_programs}" = 1 ]; then cp "${build}/fuzz/reproducer_round_trip" "${OUT}/"; fi
# OpenImageIO is loaded on first use from this module, looked for beside the program first.
cp "${build}/libshadowcts_oiio.so" "${OUT}/"
# EXR files are git-ignored: the G-buffer seeds are written by the project's own writer.
"${build}/fuzz/write_gbuffer_seeds" "${OUT}/fuzz_gbuffer_exr_seed_corpus"
# Deep-nesting JSON seeds are several hundred KB: generated, not committed.
"${build}/fuzz/write_nesting_seeds" "${OUT}/fuzz_gltf_loader_seed_corpus" \
  "${OUT}/fuzz_case_manifest_seed_corpus"
# OSS-Fuzz picks seed corpora up as <target>_seed_corpus.zip.
if command -v zip >/dev/null; then
  for target in "${targets[@]}"; do
    (cd "${OUT}/${target}_seed_corpus" && zip -q -r "../${target}_seed_corpus.zip" .)
  done
fi
echo "fuzz targets in ${OUT}"
