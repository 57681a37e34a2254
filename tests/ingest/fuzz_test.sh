#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (weather_ingest/fuzz, a separate project) and runs each briefly on
# a seed corpus. usage: fuzz_test.sh build|grib|snapshot|snapshot_crafted SOURCE_DIR BUILD_DIR [SECONDS]
# (77 = skipped; snapshot_crafted runs on the snapshot seeds with their headers made valid)
# The runs use a fixed seed and a fixed number of inputs, so a CI failure reproduces; SECONDS caps the time.
set -u
mode=$1; src=$2; build=$3; seconds=${4:-8}
case $mode in
build)
  command -v clang++ >/dev/null || { echo "SKIP: clang++ not installed"; exit 77; }
  probe=$(mktemp -d)
  echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' > "$probe/p.cpp"
  if ! clang++ -fsanitize=fuzzer,address "$probe/p.cpp" -o "$probe/p" 2>"$probe/err"; then
    echo "SKIP: clang's libFuzzer is unavailable (libclang-rt-dev?): $(head -1 "$probe/err")"; rm -rf "$probe"; exit 77
  fi
  rm -rf "$probe"
  cmake -S "$src/weather_ingest/fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DSKY_SOURCE_DIR="$src" >/dev/null || exit 1
  cmake --build "$build" -j2 || exit 1
  rm -rf "$build/seeds" && "$build/make_seeds" "$build/seeds" || exit 1
  echo "built fuzzers and seeds in $build";;
grib|snapshot|snapshot_crafted)
  [ -x "$build/fuzz_$mode" ] || { echo "SKIP: fuzzers not built"; exit 77; }
  corpus=$build/corpus-$mode
  rm -rf "$corpus"; mkdir -p "$corpus"; cp "$build/seeds/${mode%_crafted}/"* "$corpus/"
  # ecCodes keeps process-wide caches (definitions, samples) that LeakSanitizer reports as leaks.
  runs=3000; [ "$mode" != grib ] && runs=100000
  ASAN_OPTIONS=detect_leaks=0 "$build/fuzz_$mode" "$corpus" -seed=1 -runs=$runs -max_total_time="$seconds" -max_len=65536 \
      -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$build/" 2>&1 | tail -25
  exit "${PIPESTATUS[0]}";;
*) echo "unknown mode $mode"; exit 1;;
esac
