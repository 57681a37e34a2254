#!/usr/bin/env bash
# Shared by the libFuzzer scripts (tests/ingest, tests/cigi, tests/service: fuzz_test.sh), sourced:
#   build_fuzz_project PROJECT_DIR BUILD_DIR SOURCE_ROOT   configure and build a clang libFuzzer project
#                                                           (exits 77 = skipped when clang or libFuzzer is absent)
#   run_fuzzer BINARY CORPUS SEEDS RUNS SECONDS MAX_LEN [libFuzzer options...]
#       copies SEEDS into a fresh CORPUS and runs BINARY with a fixed seed and input count (a CI failure
#       reproduces), SECONDS capping the time; exits with the fuzzer's status
build_fuzz_project() {
  local project=$1 build=$2 root=$3 probe
  command -v clang++ >/dev/null || { echo "SKIP: clang++ not installed"; exit 77; }
  probe=$(mktemp -d)
  echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' > "$probe/p.cpp"
  if ! clang++ -fsanitize=fuzzer,address "$probe/p.cpp" -o "$probe/p" 2>"$probe/err"; then
    echo "SKIP: clang's libFuzzer is unavailable (libclang-rt-dev?): $(head -1 "$probe/err")"; rm -rf "$probe"; exit 77
  fi
  rm -rf "$probe"
  cmake -S "$project" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DSKY_SOURCE_DIR="$root" >/dev/null || exit 1
  cmake --build "$build" -j2 || exit 1
}

run_fuzzer() {
  local binary=$1 corpus=$2 seeds=$3 runs=$4 seconds=$5 maxLen=$6
  shift 6
  [ -x "$binary" ] || { echo "SKIP: fuzzer not built"; exit 77; }
  rm -rf "$corpus"; mkdir -p "$corpus"; cp "$seeds"/* "$corpus/"
  "$binary" "$corpus" -seed=1 -runs="$runs" -max_total_time="$seconds" -max_len="$maxLen" \
      -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$(dirname "$binary")/" "$@" 2>&1 | tail -25
  exit "${PIPESTATUS[0]}"
}
