#!/usr/bin/env bash
# CI: builds the fuzz targets (fuzz/build.sh), checks that reproducers replay, then per target
# replays every input in fuzz/regressions/<target>/ and fuzzes it. Fails on any crash, leak,
# sanitizer report, timeout or out-of-memory (after trying every target); the failing input and
# any reproducer case land in build-fuzz/findings/.
#
# Two modes:
#   CI (default): reproducible and bounded. Each target executes a fixed number of inputs
#     (-runs, from the table below) from a fixed -seed, on a fresh corpus folder
#     (build-fuzz/ci-corpus/<target>, emptied first) plus the committed seeds and, for the
#     loaders, the assimp-testmodels files. The same commit gives the same inputs.
#   Time budget (SHADOWCTS_FUZZ_SECONDS=N): each target for N seconds with a random seed, on the
#     corpus kept between runs in build-fuzz/corpus/<target>: for long local runs that make
#     progress from run to run.
#
#   SHADOWCTS_FUZZ_SECONDS  switches to the time-budget mode (seconds per target)
#   SHADOWCTS_FUZZ_SEED     the CI mode's seed (default 1)
#   SHADOWCTS_FUZZ_NO_BUILD 1: use the targets already in build-fuzz/out (no fuzz/build.sh)
#   SHADOWCTS_FUZZ_TARGETS  space-separated subset of the targets (default: all ten)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${OUT:-${root}/build-fuzz/out}"
findings="${root}/build-fuzz/findings"
models=/usr/share/assimp/models
seconds="${SHADOWCTS_FUZZ_SECONDS:-}"
seed="${SHADOWCTS_FUZZ_SEED:-1}"

# CI mode: inputs per target (including the seed corpus), calibrated to about 15-25 s each on a
# quiet 2-core machine (fuzz/README.md has the timings).
declare -A ci_runs=(
  [fuzz_gltf_loader]=30000
  [fuzz_obj_loader]=20000
  [fuzz_off_loader]=20000
  [fuzz_ply_loader]=60000
  [fuzz_stl_loader]=14000
  [fuzz_case_manifest]=60000
  [fuzz_gbuffer_exr]=700
  [fuzz_watertight]=800
  [fuzz_degenerate]=2500
  [fuzz_differential]=2200
)
# shellcheck disable=SC2206
targets=(${SHADOWCTS_FUZZ_TARGETS:-fuzz_gltf_loader fuzz_obj_loader fuzz_off_loader fuzz_ply_loader
  fuzz_stl_loader fuzz_case_manifest fuzz_gbuffer_exr fuzz_watertight fuzz_degenerate
  fuzz_differential})

start=$(date +%s)
if [ "${SHADOWCTS_FUZZ_NO_BUILD:-0}" != 1 ]; then OUT="${out}" "${root}/fuzz/build.sh"; fi
built=$(date +%s)

rm -rf "${findings}"
mkdir -p "${findings}"
export SHADOWCTS_FUZZ_REPRODUCERS="${findings}/reproducers"
# Leaks are findings; third-party libraries' own one-time allocations are suppressed in
# lsan.supp (each entry says why).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1"
export LSAN_OPTIONS="suppressions=${root}/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
"${out}/reproducer_round_trip"

# Extra read-only seed folders per target (libFuzzer adds new inputs to the first folder only).
extra_seeds() {
  case "$1" in
    fuzz_gltf_loader)
      for d in wrongTypes SchemaFailures IndexOutOfRange MissingBin IncorrectVertexArrays \
               RecursiveNodes TestNoRootNode BoxWithInfinites-glTF-Binary BoxTextured-glTF-Embedded \
               BoxTextured-glTF-Binary; do
        [ -d "${models}/glTF2/${d}" ] && echo "${models}/glTF2/${d}"
      done ;;
    fuzz_obj_loader) [ -d "${models}/OBJ" ] && echo "${models}/OBJ" ;;
    fuzz_off_loader) [ -d "${models}/OFF" ] && echo "${models}/OFF" ;;
    fuzz_ply_loader) [ -d "${models}/PLY" ] && echo "${models}/PLY" ;;
    fuzz_stl_loader) [ -d "${models}/STL" ] && echo "${models}/STL" ;;
  esac
  return 0
}

limits=(-timeout=20 -rss_limit_mb=2560 -max_len=65536)
status=0
report=()
for target in "${targets[@]}"; do
  t0=$(date +%s)
  log="${findings}/${target}.log"
  # Every kept regression input first: each must pass.
  regressions=("${root}/fuzz/regressions/${target}"/*)
  if [ -e "${regressions[0]}" ]; then
    if ! "${out}/${target}" "${limits[@]}" -artifact_prefix="${findings}/${target}-" \
        "${regressions[@]}" > "${findings}/${target}.regressions.log" 2>&1; then
      echo "fuzz: ${target} FAILED on a kept regression input" \
        "(log: ${findings}/${target}.regressions.log)"
      tail -n 40 "${findings}/${target}.regressions.log"
      status=1
    fi
  fi
  if [ -n "${seconds}" ]; then
    corpus="${root}/build-fuzz/corpus/${target}"
    mkdir -p "${corpus}"
    mode=(-max_total_time="${seconds}")
  else
    corpus="${root}/build-fuzz/ci-corpus/${target}"
    rm -rf "${corpus}"
    mkdir -p "${corpus}"
    mode=(-seed="${seed}" -runs="${ci_runs[${target}]}")
  fi
  # shellcheck disable=SC2046
  if ! "${out}/${target}" "${corpus}" "${out}/${target}_seed_corpus" $(extra_seeds "${target}") \
      "${mode[@]}" "${limits[@]}" -print_final_stats=1 \
      -artifact_prefix="${findings}/${target}-" > "${log}" 2>&1; then
    echo "fuzz: ${target} FAILED (log: ${log})"
    tail -n 60 "${log}"
    status=1
    result=FAILED
  else
    result=ok
  fi
  t1=$(date +%s)
  executed=$(grep -a -m1 -o 'stat::number_of_executed_units: [0-9]*' "${log}" | awk '{print $2}')
  line="${target}: ${result}, ${executed:-?} inputs in $((t1 - t0)) s"
  echo "fuzz: ${line}"
  report+=("${line}")
done
end=$(date +%s)
echo "fuzz: ${seconds:+time budget ${seconds} s per target}${seconds:-CI mode, seed ${seed}}"
printf 'fuzz:   %s\n' "${report[@]}"
echo "fuzz: build $((built - start)) s, runs $((end - built)) s, total $((end - start)) s"
exit "${status}"
