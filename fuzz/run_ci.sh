#!/usr/bin/env bash
# CI: builds the fuzz targets (fuzz/build.sh), checks that reproducers replay, then runs every
# target for a fixed budget on its seeds (committed seeds, plus the real and malformed files of
# Debian's assimp-testmodels for the loaders). Fails on the first crash, leak, sanitizer report,
# timeout or out-of-memory; the crashing input and any reproducer case land in
# build-fuzz/findings/.
#   SHADOWCTS_FUZZ_SECONDS  budget per target (default 45)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${SHADOWCTS_FUZZ_SECONDS:-45}"
out="${OUT:-${root}/build-fuzz/out}"
findings="${root}/build-fuzz/findings"
models=/usr/share/assimp/models

start=$(date +%s)
OUT="${out}" "${root}/fuzz/build.sh"
built=$(date +%s)

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

status=0
for target in fuzz_gltf_loader fuzz_obj_loader fuzz_off_loader fuzz_ply_loader fuzz_stl_loader \
              fuzz_case_manifest fuzz_gbuffer_exr fuzz_watertight fuzz_degenerate \
              fuzz_differential; do
  corpus="${root}/build-fuzz/corpus/${target}"
  mkdir -p "${corpus}"
  # shellcheck disable=SC2046
  if ! "${out}/${target}" "${corpus}" "${out}/${target}_seed_corpus" $(extra_seeds "${target}") \
      -max_total_time="${seconds}" -timeout=20 -rss_limit_mb=2560 -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="${findings}/${target}-" \
      > "${findings}/${target}.log" 2>&1; then
    echo "fuzz: ${target} FAILED (log: ${findings}/${target}.log)"
    tail -n 60 "${findings}/${target}.log"
    status=1
  else
    echo "fuzz: ${target} ok ($(grep -m1 -o 'stat::number_of_executed_units: [0-9]*' \
      "${findings}/${target}.log" | awk '{print $2}') runs)"
  fi
done
end=$(date +%s)
echo "fuzz: build $((built - start)) s, runs $((end - built)) s, total $((end - start)) s"
exit "${status}"
