#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (weather_ingest/fuzz, a separate project) and runs each briefly on
# a seed corpus. usage: fuzz_test.sh build|grib|snapshot|snapshot_crafted SOURCE_DIR BUILD_DIR [SECONDS]
# (77 = skipped; snapshot_crafted runs on the snapshot seeds with their headers made valid)
# The runs use a fixed seed and a fixed number of inputs, so a CI failure reproduces; SECONDS caps the time.
set -u
. "$(dirname "$0")/../fuzz_common.sh"
mode=$1; src=$2; build=$3; seconds=${4:-8}
case $mode in
build)
  build_fuzz_project "$src/weather_ingest/fuzz" "$build" "$src"
  rm -rf "$build/seeds" && "$build/make_seeds" "$build/seeds" || exit 1
  echo "built fuzzers and seeds in $build";;
grib|snapshot|snapshot_crafted)
  # ecCodes keeps process-wide caches (definitions, samples) that LeakSanitizer reports as leaks.
  runs=3000; [ "$mode" != grib ] && runs=100000
  ASAN_OPTIONS=detect_leaks=0 run_fuzzer "$build/fuzz_$mode" "$build/corpus-$mode" "$build/seeds/${mode%_crafted}" \
      $runs "$seconds" 65536;;
*) echo "unknown mode $mode"; exit 1;;
esac
