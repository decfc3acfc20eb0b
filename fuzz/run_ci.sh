#!/usr/bin/env bash
# CI: builds the fuzz targets (fuzz/build.sh), checks that reproducers replay, then per target
# replays every input in fuzz/regressions/<target>/ and fuzzes it. Fails on any crash, leak,
# sanitizer report, timeout or out-of-memory (after trying every target); the failing input and
# any reproducer case land in build-fuzz/findings/.
#
# Two modes:
#   CI (default): reproducible and bounded. Each target's <target>_ci program
#     (support/ci_driver.cpp) executes the committed seeds (and, for the loaders, the
#     assimp-testmodels files) in path order, then a fixed number of inputs (from the table below)
#     generated from a fixed seed by seeded mutation, with no coverage feedback: the same commit
#     executes the same inputs in the same order, whatever the threads do. libFuzzer's own loop is
#     not reproducible (its path follows coverage, which moves with thread interleavings). The
#     mode first checks that: one target runs twice and must print the same input digest.
#   Time budget (SHADOWCTS_FUZZ_SECONDS=N): libFuzzer's coverage-guided loop, each target for N
#     seconds with a random seed, on the corpus kept between runs in build-fuzz/corpus/<target>:
#     for long local runs that make progress from run to run.
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

# CI mode: generated inputs per target (after the seeds), calibrated to about 20 s each on a
# quiet 2-core machine (fuzz/README.md has the timings; recalibrated when the emulated CUDA
# backends joined every geometry property and the runs had grown to 545 s), and the longest input
# per target: the loaders of nested formats take deep-nesting seeds of several hundred KB
# (seeds/write_nesting_seeds.cpp). Long runs belong to the time-budget mode.
declare -A ci_runs=(
  [fuzz_gltf_loader]=8000
  [fuzz_obj_loader]=14000
  [fuzz_off_loader]=14000
  [fuzz_ply_loader]=22000
  [fuzz_stl_loader]=12000
  [fuzz_case_manifest]=7000
  [fuzz_gbuffer_exr]=130
  [fuzz_watertight]=400
  [fuzz_degenerate]=1100
  [fuzz_differential]=650
)
declare -A max_len=([fuzz_gltf_loader]=1048576 [fuzz_case_manifest]=1048576)
# shellcheck disable=SC2206
targets=(${SHADOWCTS_FUZZ_TARGETS:-fuzz_gltf_loader fuzz_obj_loader fuzz_off_loader fuzz_ply_loader
  fuzz_stl_loader fuzz_case_manifest fuzz_gbuffer_exr fuzz_watertight fuzz_degenerate
  fuzz_differential})

start=$(date +%s)
if [ "${SHADOWCTS_FUZZ_NO_BUILD:-0}" != 1 ]; then
  SHADOWCTS_FUZZ_WERROR=ON OUT="${out}" "${root}/fuzz/build.sh"
fi
built=$(date +%s)

rm -rf "${findings}"
mkdir -p "${findings}"
export SHADOWCTS_FUZZ_REPRODUCERS="${findings}/reproducers"
# Leaks are findings; third-party libraries' own one-time allocations are suppressed in
# lsan.supp (each entry says why).
# Memory: an input that holds more than 2.5 GB, or asks for it at once, is a finding (libFuzzer's
# -rss_limit_mb and -malloc_limit_mb in the CI programs, which run without libFuzzer).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1:hard_rss_limit_mb=2560:max_allocation_size_mb=2560:allocator_may_return_null=0"
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

# Seconds an input may take before it counts as a hang. The CI mode's inputs are fixed and take a
# few seconds at most. The time-budget mode's coverage-guided ones reach further: on sun-disk
# cases the exact soft-shadow oracle (GMP rationals, whose every allocation ASan records with its
# stack) took up to 15 CPU-seconds, and twice passed 20 s of wall time on a shared machine, so
# that mode waits 60 s.
timeout=20
[ -n "${seconds}" ] && timeout=60
limits=(-timeout="${timeout}" -rss_limit_mb=2560 -max_len=65536)
status=0
report=()

# Reproducibility of the CI mode, checked where it matters: the same program, seed and count run
# twice must execute the same inputs (the digest on the last line).
if [ -z "${seconds}" ]; then
  check_target=fuzz_watertight
  check=()
  for k in 1 2; do
    check+=("$("${out}/${check_target}_ci" --seed "${seed}" --runs 100 \
      --artifact-prefix "${findings}/${check_target}-" "${out}/${check_target}_seed_corpus" \
      2> "${findings}/determinism-${k}.log" | tail -n 1 | sed 's/, [0-9.]* s,/,/' || true)")
  done
  if [ "${check[0]}" != "${check[1]}" ] || [ -z "${check[0]}" ]; then
    echo "fuzz: the CI mode is NOT reproducible: two runs of ${check_target}_ci printed"
    printf '  %s\n' "${check[@]}"
    status=1
  else
    echo "fuzz: CI mode reproducible (${check_target}, two runs): ${check[0]#ci-fuzz: }"
  fi
fi

for target in "${targets[@]}"; do
  t0=$(date +%s)
  log="${findings}/${target}.log"
  regressions=("${root}/fuzz/regressions/${target}"/*)
  [ -e "${regressions[0]}" ] || regressions=()
  result=0
  if [ -n "${seconds}" ]; then
    # Every kept regression input first: each must pass.
    if ((${#regressions[@]})) && ! "${out}/${target}" "${limits[@]}" \
        -artifact_prefix="${findings}/${target}-" "${regressions[@]}" \
        > "${findings}/${target}.regressions.log" 2>&1; then
      echo "fuzz: ${target} FAILED on a kept regression input" \
        "(log: ${findings}/${target}.regressions.log)"
      tail -n 40 "${findings}/${target}.regressions.log"
      status=1
    fi
    corpus="${root}/build-fuzz/corpus/${target}"
    mkdir -p "${corpus}"
    # shellcheck disable=SC2046
    "${out}/${target}" "${corpus}" "${out}/${target}_seed_corpus" $(extra_seeds "${target}") \
      -max_total_time="${seconds}" "${limits[@]}" -print_final_stats=1 \
      -artifact_prefix="${findings}/${target}-" > "${log}" 2>&1 || result=$?
    executed=$(grep -a -m1 -o 'stat::number_of_executed_units: [0-9]*' "${log}" |
      awk '{print $2}' || true)
  else
    # Regression inputs first, then the seeds, then the generated inputs; all must pass.
    # shellcheck disable=SC2046
    "${out}/${target}_ci" --seed "${seed}" --runs "${ci_runs[${target}]}" --timeout "${timeout}" \
      --max-len "${max_len[${target}]:-65536}" --artifact-prefix "${findings}/${target}-" \
      "${regressions[@]}" "${out}/${target}_seed_corpus" $(extra_seeds "${target}") \
      > "${log}" 2>&1 || result=$?
    executed=$(grep -a -o 'ok: [0-9]* seed inputs + [0-9]* generated' "${log}" | tail -n 1 |
      awk '{print $2 + $6}' || true)
  fi
  if [ "${result}" != 0 ]; then
    echo "fuzz: ${target} FAILED (log: ${log})"
    tail -n 60 "${log}"
    status=1
    result=FAILED
  else
    result=ok
  fi
  t1=$(date +%s)
  line="${target}: ${result}, ${executed:-?} inputs in $((t1 - t0)) s"
  echo "fuzz: ${line}"
  report+=("${line}")
done
end=$(date +%s)
echo "fuzz: ${seconds:+time budget ${seconds} s per target}${seconds:-CI mode, seed ${seed}}"
printf 'fuzz:   %s\n' "${report[@]}"
echo "fuzz: build $((built - start)) s, runs $((end - built)) s, total $((end - start)) s"
exit "${status}"
