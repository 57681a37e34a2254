#!/usr/bin/env bash
# Builds the daemon's libFuzzer targets with clang (skyservice/service/fuzz, a separate project) and runs
# each briefly on a seed corpus. usage: fuzz_test.sh build|protocol|service_config SOURCE_DIR BUILD_DIR [SECONDS]
# (77 = skipped). The runs use a fixed seed and a fixed number of inputs, so a CI failure reproduces;
# SECONDS caps the time.
set -u
. "$(dirname "$0")/../fuzz_common.sh"
mode=$1; src=$2; build=$3; seconds=${4:-8}
case $mode in
build)
  build_fuzz_project "$src/skyservice/service/fuzz" "$build" "$src"
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
  runs=100000; [ "$mode" = service_config ] && runs=20000
  run_fuzzer "$build/fuzz_$mode" "$build/corpus-$mode" "$build/seeds/$mode" $runs "$seconds" 65536;;
*) echo "unknown mode $mode"; exit 1;;
esac
