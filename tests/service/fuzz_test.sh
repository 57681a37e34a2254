#!/usr/bin/env bash
# Builds the daemon's libFuzzer targets with clang (skyservice/service/fuzz, a separate project) and runs
# each briefly on a seed corpus. usage: fuzz_test.sh build|protocol|service_config SOURCE_DIR BUILD_DIR [SECONDS]
# (77 = skipped). The runs use a fixed seed and a fixed number of inputs, so a CI failure reproduces;
# SECONDS caps the time.
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
  cmake -S "$src/skyservice/service/fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DSKY_SOURCE_DIR="$src" >/dev/null || exit 1
  cmake --build "$build" -j2 || exit 1
  # Seeds: one valid request of each type, and the example config.
  rm -rf "$build/seeds" && mkdir -p "$build/seeds/protocol" "$build/seeds/service_config" || exit 1
  i=0
  while IFS= read -r line; do
    i=$((i + 1)); printf '%s' "$line" > "$build/seeds/protocol/$i"
  done <<'LINES'
{"type":"hello","protocol":1,"client":"ig","id":1}
{"type":"set_view","view":{"lat":47.5,"lon":8.5,"alt":1500,"heading":270,"pitch":5,"fov":60,"width":320},"id":"a"}
{"type":"set_time","time":"2026-06-21T12:00:00Z","rate":60}
{"type":"load_weather","path":"/srv/weather/gfs.skywx"}
{"type":"subscribe","transport":"shm","layers":["display","clouds","depth"]}
{"type":"subscribe","transport":"files","dir":"shots","every":5,"format":"both"}
{"type":"subscribe","transport":"vulkan"}
{"type":"render"}
{"type":"status","id":7}
{"type":"write_files","prefix":"shots/a"}
LINES
  cp "$src/config/service.toml" "$build/seeds/service_config/example.toml" || exit 1
  printf '[service]\nrender_rate_hz = 5\nfiles_every = 2\nfiles_dir = "x"\n[march]\nmax_view_steps = 64\n' \
      > "$build/seeds/service_config/small.toml"
  echo "built the service fuzzers and seeds in $build";;
protocol|service_config)
  [ -x "$build/fuzz_$mode" ] || { echo "SKIP: fuzzers not built"; exit 77; }
  corpus=$build/corpus-$mode
  rm -rf "$corpus"; mkdir -p "$corpus"; cp "$build/seeds/$mode/"* "$corpus/"
  runs=100000; [ "$mode" = service_config ] && runs=20000
  "$build/fuzz_$mode" "$corpus" -seed=1 -runs=$runs -max_total_time="$seconds" -max_len=65536 \
      -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$build/" 2>&1 | tail -25
  exit "${PIPESTATUS[0]}";;
*) echo "unknown mode $mode"; exit 1;;
esac
