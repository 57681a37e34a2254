#!/usr/bin/env bash
# Builds the CIGI decoder's libFuzzer target with clang (skyservice/cigi/fuzz, a separate project) and runs it
# briefly on a seed corpus. usage: fuzz_test.sh build|decoder SOURCE_DIR BUILD_DIR [SECONDS]   (77 = skipped)
# The run uses a fixed seed and a fixed number of inputs, so a CI failure reproduces; SECONDS caps the time.
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
  cmake -S "$src/skyservice/cigi/fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DSKY_SOURCE_DIR="$src" >/dev/null || exit 1
  cmake --build "$build" -j2 || exit 1
  rm -rf "$build/seeds" && "$build/make_cigi_seeds" "$build/seeds" || exit 1
  echo "built the CIGI fuzzer and seeds in $build";;
decoder)
  [ -x "$build/fuzz_cigi_decoder" ] || { echo "SKIP: fuzzer not built"; exit 77; }
  corpus=$build/corpus
  rm -rf "$corpus"; mkdir -p "$corpus"; cp "$build/seeds/"* "$corpus/"
  # A UDP datagram is at most 65507 bytes.
  "$build/fuzz_cigi_decoder" "$corpus" -seed=1 -runs=200000 -max_total_time="$seconds" -max_len=65507 \
      -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$build/" 2>&1 | tail -25
  exit "${PIPESTATUS[0]}";;
*) echo "unknown mode $mode"; exit 1;;
esac
