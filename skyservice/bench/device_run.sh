#!/bin/bash
# sky-bench on the GPU machine (BENCHMARKS.md "Reproduce"). Run from the repo root through the device
# tool, after skyservice/bench/device_prepare.sh, with carry [".gl", ".gpu"]:
#   bash skyservice/bench/device_run.sh
# Unpacks the carried .debs (the loader into /, build dependencies into /tmp/deps), builds sky-bench and
# the baseline there (falling back to the binaries built on the dev machine), then times both at
# 1920x1080, 640x360 and 3840x2160 and writes JSON, the baseline's log and an SM-clock log to $OUT.
set -u
# SKY_BENCH_GL_DIR and SKY_BENCH_GPU_DIR point elsewhere than .gl/ and .gpu/ (e.g. folders carried from
# another checkout: the device tool copies the session's main checkout, not a worktree).
ROOT=$PWD; G=${SKY_BENCH_GPU_DIR:-$ROOT/.gpu}; GL=${SKY_BENCH_GL_DIR:-$ROOT/.gl}; P=/tmp/deps
exec > >(tee "$OUT/log.txt") 2>&1
T0=$(date +%s); el() { echo "[t+$(( $(date +%s) - T0 ))s] $*"; }
for f in "$GL"/*.deb; do dpkg -x "$f" /; done; ldconfig
mkdir -p $P; for f in "$G"/debs/*.deb; do dpkg -x "$f" $P; done
export LD_LIBRARY_PATH=$P/usr/lib/x86_64-linux-gnu
export SKY_SPIRV_DIR=$G/spirv
el "unpacked"; uname -a; nproc; (cmake --version; g++ --version) | grep -i "version\|g++"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,power.draw,temperature.gpu --format=csv

# Build there (as GPU.md asks); the carried binaries are the fallback. SKY_BENCH_DEVICE_BUILD=0 skips
# the build of sky-bench (minutes of device time) and times the binaries built on the dev machine.
BENCH=$G/prebuilt/sky-bench; PROBE=$G/prebuilt/cloudprobe
if [ "${SKY_BENCH_DEVICE_BUILD:-1}" = 0 ]; then
  el "no device build: using the carried sky-bench"
elif timeout 60 cmake -S "$ROOT" -B /tmp/build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKY_BUILD_TESTS=OFF \
     -DSKY_BUILD_INGEST=OFF -DSKY_PREBUILT_SPIRV_DIR=$G/spirv -DVulkan_INCLUDE_DIR=$G/include \
     -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 -DCMAKE_PREFIX_PATH=$P/usr \
     -DCMAKE_MODULE_PATH=$P/usr/share/cmake/geographiclib "-DCMAKE_CXX_FLAGS=-isystem $P/usr/include" \
     -DPKG_CONFIG_EXECUTABLE=$P/usr/bin/pkgconf -DCMAKE_POLICY_VERSION_MINIMUM=3.5 > /tmp/cfg.log 2>&1 &&
   timeout 240 cmake --build /tmp/build --target sky-bench -j16 > /tmp/build.log 2>&1; then
  BENCH=/tmp/build/skyservice/sky-bench; el "built sky-bench on the device"
else
  el "device build FAILED, using the carried binary"; tail -30 /tmp/cfg.log; tail -40 /tmp/build.log
fi
if timeout 60 cmake -S $G/baseline -B /tmp/bb -DCMAKE_BUILD_TYPE=Release -DCLOUDPROBE_SPV=$G/baseline/cloud.comp.spv \
     -DVulkan_INCLUDE_DIR=$G/include -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 > /tmp/bcfg.log 2>&1 &&
   timeout 60 cmake --build /tmp/bb -j16 > /tmp/bbuild.log 2>&1; then
  PROBE=/tmp/bb/cloudprobe; el "built cloudprobe on the device"
else
  el "baseline build FAILED, using the carried binary"; tail -20 /tmp/bcfg.log /tmp/bbuild.log
fi

# Does the loader find the NVIDIA driver, and do binary and SPIR-V agree? If not, point the loader at
# the ICD (GPU.md), then fall back to the carried binary (built with the carried SPIR-V).
probe() { timeout 60 $BENCH --scene clear --width 64 --height 64 --frames 1 --warmup 0 --device NVIDIA > /tmp/probe.log 2>&1; }
if ! probe; then
  cat /tmp/probe.log; export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  el "retrying with VK_DRIVER_FILES"
  if ! probe; then
    cat /tmp/probe.log; BENCH=$G/prebuilt/sky-bench; el "retrying with the carried binary"
    probe || { cat /tmp/probe.log; unset VK_DRIVER_FILES; el "and without VK_DRIVER_FILES"; probe || cat /tmp/probe.log; }
  fi
fi
el "using $BENCH"

# SM clock while we measure (the GPU may idle down between calls while the CPU prepares the next).
Q=timestamp,clocks.sm,utilization.gpu,power.draw,clocks_event_reasons.active
nvidia-smi --query-gpu=$Q --format=csv -c 1 > /dev/null 2>&1 || Q=timestamp,clocks.sm,utilization.gpu,power.draw
nvidia-smi --query-gpu=$Q --format=csv,noheader -lms 200 > "$OUT/clocks.csv" 2>/dev/null &
CLK=$!

bench() {  # W H SAMPLES LIMIT_S JSON EXTRA
  el "sky-bench $1x$2 $6"
  timeout $4 $BENCH --scene all --width $1 --height $2 --frames $3 --warmup 10 --gpu-frames 4 --device NVIDIA \
    --json "$OUT/$5" $6
  el "sky-bench $1x$2 rc=$?"
}
base() {  # W H
  el "baseline $1x$2"
  timeout 120 $PROBE --spv $G/baseline/cloud.comp.spv --width $1 --height $2 --frames 100 --out /tmp/base-$1x$2 \
    2>&1 | tee -a "$OUT/baseline.txt" | grep -i "using device\|driver\|FULL\|1/16\|timestamp"
}
MODE=${SKY_BENCH_MODE:-full}  # full | reprojected | both (both: reprojected at 1080p and 4K, then full at 1080p) | ab | builds
if [ "$MODE" = builds ]; then
  # A/B of sky-bench builds in one call (the main branch against a change of a shader and its dispatch):
  # each .gpu/builds/<label>/ holds a sky-bench and its SPIR-V (device_prepare.sh, SKY_BENCH_BUILDS).
  # 100 frames after 20 warm-up (full mode: 10, and 4 GPU frames per sample) in each of
  # SKY_BENCH_AB_MODES (default reprojected), at each of SKY_BENCH_AB_SIZES (default 1920x1080),
  # SKY_BENCH_SCENES (default all), and each option set of SKY_BENCH_VARIANTS (';'-separated, as in ab
  # mode); the builds take turns inside each size and option set, so that clock drift hits them alike.
  # Writes bench-<label>-<W>x<H>-v<i>.json (full mode: bench-<label>-full-<W>x<H>-v<i>.json), then the
  # baseline at each size.
  IFS=';' read -ra VARIANTS <<< "${SKY_BENCH_VARIANTS:- }"
  for m in ${SKY_BENCH_AB_MODES:-reprojected}; do
    if [ "$m" = reprojected ]; then extra="--warmup 20"; tag=""; else extra="--warmup 10 --gpu-frames 4"; tag="full-"; fi
    for size in ${SKY_BENCH_AB_SIZES:-1920x1080}; do
      w=${size%x*}; h=${size#*x}; i=0
      for v in "${VARIANTS[@]}"; do
        for dir in "$G"/builds/*/; do
          label=$(basename "$dir")
          el "sky-bench $label $m ${w}x$h v$i: $v"
          # shellcheck disable=SC2086
          SKY_SPIRV_DIR=$dir/spirv timeout ${SKY_BENCH_RUN_LIMIT_S:-60} "$dir/sky-bench" --scene "${SKY_BENCH_SCENES:-all}" \
            --width $w --height $h --frames 100 $extra --mode $m --device NVIDIA \
            --json "$OUT/bench-$label-$tag${w}x$h-v$i.json" $v | grep -v "MiB$"
          el "rc=${PIPESTATUS[0]}"
        done
        i=$((i + 1))
      done
    done
  done
  for size in ${SKY_BENCH_AB_SIZES:-1920x1080}; do base ${size%x*} ${size#*x}; done
  kill $CLK
  el "done"
  exit 0
fi
if [ "$MODE" = ab ]; then
  # A/B of sky-bench options in one call: SKY_BENCH_VARIANTS holds option sets separated by ';' (e.g.
  # "--march-threads 1;--march-threads 4"); each runs in SKY_BENCH_AB_MODES (default: reprojected full)
  # at 1920x1080, as bench-ab<i>-<mode>.json; the baseline at 1920x1080 after.
  i=0
  IFS=';' read -ra VARIANTS <<< "${SKY_BENCH_VARIANTS:-}"
  for v in "${VARIANTS[@]}"; do
    for m in ${SKY_BENCH_AB_MODES:-reprojected full}; do
      el "sky-bench ab$i $m: $v"
      if [ "$m" = reprojected ]; then extra="--warmup 20"; else extra="--warmup 10 --gpu-frames 4"; fi
      # shellcheck disable=SC2086
      timeout 200 $BENCH --scene all --width 1920 --height 1080 --frames 100 $extra --mode $m --device NVIDIA \
        --json "$OUT/bench-ab$i-$m.json" $v | grep -v "MiB$"
      el "rc=${PIPESTATUS[0]}"  # sky-bench's, not grep's
    done
    i=$((i + 1))
  done
  base 1920 1080
  kill $CLK
  el "done"
  exit 0
fi
if [ "$MODE" = reprojected ] || [ "$MODE" = both ]; then
  # Temporal reprojection: one GPU frame per call (a frame needs the one before), so the GPU may clock
  # down during the CPU setup between frames: read the clock log next to the figures.
  bench() {
    el "sky-bench reprojected $1x$2"
    timeout $4 $BENCH --scene all --width $1 --height $2 --frames $3 --warmup 20 --mode reprojected \
      --device NVIDIA --json "$OUT/$5"
    el "sky-bench $1x$2 rc=$?"
  }
  bench 1920 1080 100 200 bench-reprojected-1920x1080.json
  base 1920 1080
  bench 3840 2160 50 200 bench-reprojected-3840x2160.json
  base 3840 2160
  if [ "$MODE" = both ]; then
    el "sky-bench full 1920x1080"
    timeout 180 $BENCH --scene all --width 1920 --height 1080 --frames 100 --warmup 10 --gpu-frames 4 \
      --device NVIDIA --json "$OUT/bench-1920x1080.json"
    el "sky-bench full rc=$?"
  fi
  kill $CLK
  el "done"
  exit 0
fi
bench 1920 1080 100 180 bench-1920x1080.json ""
base 1920 1080
bench 640 360 100 150 bench-640x360.json ""
base 640 360
bench 3840 2160 30 150 bench-3840x2160.json ""
base 3840 2160
bench 1920 1080 20 90 bench-1920x1080-shadow.json --shadow-map
kill $CLK
el "done"
