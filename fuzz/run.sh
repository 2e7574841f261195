#!/usr/bin/env bash
# Builds the fuzz targets with clang (libFuzzer + ASan + UBSan; ccache when present) in
# $FUZZ_BUILD (default build-fuzz/) and runs each, one after the other, for SECONDS (default 60)
# on a temporary copy of its corpus (fuzz/corpus/<target>/), so the source tree stays clean: only
# $FUZZ_BUILD is written. Exits non-zero on any finding (crash, sanitizer report, failed check,
# 10 s timeout, more than 2 GiB allocated); crash inputs are kept in $FUZZ_BUILD/findings/.
# FUZZ_SEED (default 1) fixes the mutation sequence, so a CI run repeats the inputs a local run of
# the same length tried first; FUZZ_SEED=0 lets libFuzzer pick one (long local runs).
# Usage: fuzz/run.sh [SECONDS] [TARGET...]
#   targets: text ply off obj stl geojson (readers), reconstruct2 reconstruct3 surfaces3 gamma_graph (engines),
#   compare3 (the mesh comparison);
#   docs/fuzzing.md. MAX_LEN (default 4096) bounds the input size; fuzz/dict/<target>.dict is
#   passed as -dict when it exists. KEEP_CORPUS=1 fuzzes $FUZZ_BUILD/corpus/<target>/ (seeded from
#   fuzz/corpus/) instead of a temporary copy, so long runs continue where the last one stopped.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(text ply off obj stl geojson reconstruct2 reconstruct3 surfaces3 gamma_graph compare3)
BUILD=${FUZZ_BUILD:-build-fuzz}
JOBS=${JOBS:-2}

LAUNCHER=()
command -v ccache >/dev/null 2>&1 && LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=${CC:-clang-14} CXX=${CXX:-clang++-14} cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "${LAUNCHER[@]}" -DCONSTRICT_BUILD_FUZZ=ON -DCONSTRICT_BUILD_TESTS=OFF -DCONSTRICT_BUILD_PYTHON=OFF \
  -DCONSTRICT_BUILD_CLI=OFF >/dev/null
cmake --build "$BUILD" -j "$JOBS" --target $(printf 'fuzz_%s ' "${TARGETS[@]}")

mkdir -p "$BUILD/findings"
status=0
for t in "${TARGETS[@]}"; do
  work=$(mktemp -d)
  if [ -n "${KEEP_CORPUS:-}" ]; then  # a corpus that grows from run to run, under $BUILD
    mkdir -p "$BUILD/corpus/$t"
    cp -n "fuzz/corpus/$t/"* "$BUILD/corpus/$t/"
    ln -s "$(cd "$BUILD/corpus/$t" && pwd)" "$work/corpus"
  else
    cp -r "fuzz/corpus/$t" "$work/corpus"
  fi
  dict=()
  [ -f "fuzz/dict/$t.dict" ] && dict=(-dict="fuzz/dict/$t.dict")
  echo "== fuzz_$t: ${SECONDS_EACH}s"
  if ! "$BUILD/fuzz/fuzz_$t" "$work/corpus" "${dict[@]}" -max_total_time="$SECONDS_EACH" -seed="${FUZZ_SEED:-1}" -timeout=10 \
       -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len="${MAX_LEN:-4096}" -print_final_stats=1 \
       -artifact_prefix="$BUILD/findings/${t}-" 2>"$work/log"; then
    status=1
    echo "!! fuzz_$t: finding (log: $BUILD/findings/$t.log)"
    grep -E "^(==[0-9]+==ERROR|SUMMARY|fuzz contract|fuzz check|artifact_prefix|Test unit written)" "$work/log" | head -5 || true
  fi
  grep -E "^#[0-9]+.*(DONE|cov:)" "$work/log" | tail -1 || true
  grep -E "stat::number_of_executed_units" "$work/log" || true
  cp "$work/log" "$BUILD/findings/$t.log"
  rm -rf "$work"
done
exit $status
