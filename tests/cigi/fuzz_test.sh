#!/usr/bin/env bash
# Builds the CIGI decoder's libFuzzer target with clang (skyservice/cigi/fuzz, a separate project) and runs it
# briefly on a seed corpus. usage: fuzz_test.sh build|decoder SOURCE_DIR BUILD_DIR [SECONDS]   (77 = skipped)
# The run uses a fixed seed and a fixed number of inputs, so a CI failure reproduces; SECONDS caps the time.
set -u
. "$(dirname "$0")/../fuzz_common.sh"
mode=$1; src=$2; build=$3; seconds=${4:-8}
case $mode in
build)
  build_fuzz_project "$src/skyservice/cigi/fuzz" "$build" "$src"
  rm -rf "$build/seeds" && "$build/make_cigi_seeds" "$build/seeds" || exit 1
  echo "built the CIGI fuzzer and seeds in $build";;
decoder)
  # A UDP datagram is at most 65507 bytes.
  run_fuzzer "$build/fuzz_cigi_decoder" "$build/corpus" "$build/seeds" 200000 "$seconds" 65507;;
*) echo "unknown mode $mode"; exit 1;;
esac
