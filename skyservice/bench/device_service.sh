#!/bin/bash
# sky-service-bench on the GPU machine (skyservice/bench/README-service.md). Two steps:
#   here, on the dev machine, from the repo root (needs a configured build folder, default build-bench):
#     bash skyservice/bench/device_service.sh prepare [BUILD]
#   there, through the device tool with carry [".gl", ".gpu"], from the repo root:
#     bash skyservice/bench/device_service.sh
# prepare makes .gl/ and .gpu/ with device_prepare.sh when they are absent (loader, headers, build
# dependencies as .debs, the baseline), adds toml++ (the daemon's config reader; header-only), and
# refreshes .gpu/spirv from BUILD. On the device it builds skyservice (the daemon), sky-service-bench and
# sky-bench without the ingest decoders (-DSKY_BUILD_INGEST=OFF: the device has no ecCodes/netCDF; the
# bench writes its synthetic weather with sky_weather, which needs neither), then runs the plan below
# and writes service-*.json, bench-reprojected-*.json, clocks.csv and service-log.txt to $OUT.
# Knobs (environment): SKY_SVC_RUNS (which runs, default all of them, in this order:
# "1080p 1080p-layers 1080p-layers-vulkan 1080p-shadow 4k 640 rate1000 sky-bench baseline"; "flight" the flight
# path at 1080p over shm (flight-*.json and the frames' flight-*.csv; SKY_SVC_FLIGHT_STEP simulated s per frame,
# default 1/60: 14,400 frames), "before-flight" the same with the earlier tree's daemon; "before" runs
# 1080p shm with an earlier tree prepared with `prepare-before REV`, the frame path before a change, in the same
# call; "before-both" its shm and Vulkan transports, "before-shadow" with a 1024² shadow map, "sky-bench-before"
# the renderer alone with the earlier tree; "sky-bench@NAME" the renderer with the SPIR-V in .gpu/spirv-NAME,
# for shader-only variants built here (sky-bench@NAME+OPTIONS with options); "sky-bench+OPTIONS" and "sky-bench-before+OPTIONS" with more sky-bench
# options, commas for spaces, e.g. sky-bench+--full-cone-samples,1), SKY_SVC_FRAMES (timed frames per scene, size and
# transport; default 300), SKY_SVC_SCENES (default all), SKY_SVC_LIMIT_S (each run's time limit, default
# 150 s), SKY_SVC_BUILD=0 (reuse /tmp/build from an earlier call on the same warm machine). A device call
# lasts at most 10 minutes: with a slow frame path, lower SKY_SVC_FRAMES or split SKY_SVC_RUNS over calls.
set -u
if [ "${1:-}" = prepare-before ]; then  # REV [BUILD]: .gpu/before/{src,spirv} from git revision REV
  set -e
  REV=${2:?a git revision}; BUILD=${3:-build-before}
  rm -rf .gpu/before && mkdir -p .gpu/before/src
  git archive "$REV" | tar -x -C .gpu/before/src
  cmake -S .gpu/before/src -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKY_BUILD_TESTS=OFF > /dev/null
  cmake --build "$BUILD" --target sky_shaders -j2
  cp -r "$BUILD/spirv" .gpu/before/spirv
  du -sh .gpu/before
  exit 0
fi
if [ "${1:-}" = prepare ]; then
  set -e
  BUILD=${2:-build-bench}
  [ -d .gpu/debs ] && [ -d .gl ] || bash skyservice/bench/device_prepare.sh "$BUILD"
  (cd .gpu/debs && apt-get download libtomlplusplus-dev)
  cmake --build "$BUILD" --target sky_shaders -j2
  rm -rf .gpu/spirv && cp -r "$BUILD/spirv" .gpu/spirv
  du -sh .gl .gpu
  exit 0
fi

ROOT=$PWD; G=${SKY_BENCH_GPU_DIR:-$ROOT/.gpu}; GL=${SKY_BENCH_GL_DIR:-$ROOT/.gl}; P=/tmp/deps
exec > >(tee "$OUT/service-log.txt") 2>&1
T0=$(date +%s); el() { echo "[t+$(( $(date +%s) - T0 ))s] $*"; }
for f in "$GL"/*.deb; do dpkg -x "$f" /; done; ldconfig
mkdir -p $P; for f in "$G"/debs/*.deb; do dpkg -x "$f" $P; done
export LD_LIBRARY_PATH=$P/usr/lib/x86_64-linux-gnu
export SKY_SPIRV_DIR=$G/spirv
el "unpacked"; nproc
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,power.draw,temperature.gpu --format=csv

if [ "${SKY_SVC_BUILD:-1}" != 0 ]; then
  if timeout 60 cmake -S "$ROOT" -B /tmp/build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKY_BUILD_TESTS=OFF \
       -DSKY_BUILD_INGEST=OFF -DSKY_PREBUILT_SPIRV_DIR=$G/spirv -DVulkan_INCLUDE_DIR=$G/include \
       -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 -DCMAKE_PREFIX_PATH=$P/usr \
       -DCMAKE_MODULE_PATH=$P/usr/share/cmake/geographiclib "-DCMAKE_CXX_FLAGS=-isystem $P/usr/include" \
       -DPKG_CONFIG_EXECUTABLE=$P/usr/bin/pkgconf -DCMAKE_POLICY_VERSION_MINIMUM=3.5 > /tmp/cfg.log 2>&1 &&
     timeout 300 cmake --build /tmp/build --target skyservice sky-service-bench sky-bench -j16 \
       > /tmp/build.log 2>&1; then
    el "built skyservice, sky-service-bench and sky-bench"
  else
    el "device build FAILED"; tail -30 /tmp/cfg.log; tail -40 /tmp/build.log; exit 1
  fi
fi
SB=/tmp/build/skyservice/sky-service-bench; BENCH=/tmp/build/skyservice/sky-bench
configure() {  # SRC BUILD SPIRV
  timeout 60 cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKY_BUILD_TESTS=OFF \
    -DSKY_BUILD_INGEST=OFF -DSKY_PREBUILT_SPIRV_DIR="$3" -DVulkan_INCLUDE_DIR=$G/include \
    -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 -DCMAKE_PREFIX_PATH=$P/usr \
    -DCMAKE_MODULE_PATH=$P/usr/share/cmake/geographiclib "-DCMAKE_CXX_FLAGS=-isystem $P/usr/include" \
    -DPKG_CONFIG_EXECUTABLE=$P/usr/bin/pkgconf -DCMAKE_POLICY_VERSION_MINIMUM=3.5 > /tmp/cfg-before.log 2>&1
}
if [ -d "$G/before/src" ] && [ "${SKY_SVC_BUILD:-1}" != 0 ]; then
  if configure "$G/before/src" /tmp/build-before "$G/before/spirv" &&
     timeout 300 cmake --build /tmp/build-before --target skyservice sky-service-bench sky-bench -j16 \
      > /tmp/build-before.log 2>&1
  then el "built the earlier tree (.gpu/before)"; else el "earlier tree: build FAILED"; tail -30 /tmp/build-before.log; fi
fi

# Does the loader find the NVIDIA driver? If not, point it at the ICD (GPU.md).
probe() { timeout 120 $SB --scene clear --size 64x64 --frames 2 --warmup 1 --transport both --device NVIDIA \
  > /tmp/probe.log 2>&1; }
if ! probe; then
  cat /tmp/probe.log; export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  el "retrying with VK_DRIVER_FILES"; probe || { cat /tmp/probe.log; el "no NVIDIA device: stopping"; exit 1; }
fi
cat /tmp/probe.log

Q=timestamp,clocks.sm,utilization.gpu,power.draw,clocks_event_reasons.active
nvidia-smi --query-gpu=$Q --format=csv -c 1 > /dev/null 2>&1 || Q=timestamp,clocks.sm,utilization.gpu,power.draw
nvidia-smi --query-gpu=$Q --format=csv,noheader -lms 200 > "$OUT/clocks.csv" 2>/dev/null &
CLK=$!

FRAMES=${SKY_SVC_FRAMES:-300}; SCENES=${SKY_SVC_SCENES:-all}; LIMIT=${SKY_SVC_LIMIT_S:-150}
svc() {  # LABEL OPTIONS...
  local label=$1; shift
  el "sky-service-bench $label: $*"
  timeout "$LIMIT" $SB --scene "$SCENES" --frames "$FRAMES" --warmup 30 --device NVIDIA \
    --json "$OUT/service-$label.json" "$@"
  el "sky-service-bench $label rc=$?"
}
svcBefore() {  # LABEL OPTIONS...: the earlier tree's daemon and bench, with its own SPIR-V
  local label=$1; shift
  el "earlier tree: sky-service-bench $label: $*"
  SKY_SPIRV_DIR=$G/before/spirv timeout "$LIMIT" /tmp/build-before/skyservice/sky-service-bench --scene "$SCENES" \
    --warmup 10 --device NVIDIA --json "$OUT/service-before-$label.json" "$@"
  el "earlier tree: sky-service-bench $label rc=$?"
}
svcFlight() {  # LABEL SPIRV [OPTIONS...]: the flight path at 1080p over shm with this tree's bench
  local label=$1 spirv=$2; shift 2
  el "sky-service-bench flight path $label: $*"
  SKY_SPIRV_DIR=$spirv timeout "$LIMIT" $SB --flight-path --size 1920x1080 --transport shm --warmup 30 \
    --flight-step "${SKY_SVC_FLIGHT_STEP:-0.0166666666666667}" --device NVIDIA --json "$OUT/flight-$label.json" \
    --frames-csv "$OUT/flight-$label.csv" "$@"
  el "sky-service-bench flight path $label rc=$?"
}
skyBench() {  # SUFFIX BENCH SPIRV [OPTIONS...]
  el "sky-bench$1 reprojected 1920x1080 ${*:4}"
  SKY_SPIRV_DIR=$3 timeout "$LIMIT" "$2" --scene "$SCENES" --width 1920 --height 1080 --frames 100 --warmup 20 \
    --mode reprojected --speed 250 --steps 96 --light-samples 5 --device NVIDIA \
    --json "$OUT/bench-reprojected-1920x1080$1.json" "${@:4}" | grep -v "MiB$"
  el "sky-bench$1 rc=${PIPESTATUS[0]}"
}
for run in ${SKY_SVC_RUNS:-1080p 1080p-layers 1080p-layers-vulkan 1080p-shadow 4k 640 rate1000 sky-bench baseline}; do
  case $run in
    1080p) svc 1920x1080 --size 1920x1080 --transport both ;;
    1080p-layers) svc 1920x1080-layers --size 1920x1080 --layers display,sky,clouds,depth ;;
    1080p-layers-vulkan) svc 1920x1080-layers-vulkan --size 1920x1080 --transport vulkan \
                           --layers display,sky,clouds,depth ;;
    before) svcBefore 1920x1080 --size 1920x1080 --frames ${SKY_SVC_BEFORE_FRAMES:-30} ;;
    before-both) svcBefore 1920x1080 --size 1920x1080 --transport both --frames ${SKY_SVC_BEFORE_FRAMES:-300} ;;
    before-shadow) svcBefore 1920x1080-shadow1024 --size 1920x1080 --shadow-map 1024 \
                     --frames ${SKY_SVC_BEFORE_FRAMES:-300} ;;
    1080p-shadow) svc 1920x1080-shadow1024 --size 1920x1080 --shadow-map 1024 ;;
    flight) svcFlight 1920x1080 "$SKY_SPIRV_DIR" ;;
    before-flight)  # the earlier tree's daemon and SPIR-V flown by this tree's bench (an earlier bench has no
                    # flight path); a daemon without per-frame times in its status gives fps and frame times only
      svcFlight before-1920x1080 "$G/before/spirv" --daemon /tmp/build-before/skyservice/skyservice ;;
    4k) svc 3840x2160 --size 3840x2160 ;;
    640) svc 640x360 --size 640x360 ;;
    rate1000) svc 1920x1080-rate1000 --size 1920x1080 --rate-hz 1000 ;;
    sky-bench)  # the renderer alone: same scenes, size, eye speed and quality ("medium" = 96 steps, 5 light
                # samples); what the service adds is the difference
      skyBench "" $BENCH "$SKY_SPIRV_DIR" ;;
    sky-bench-before)  # the same with the earlier tree (a change's cost on the renderer, in the same call)
      skyBench "-before" /tmp/build-before/skyservice/sky-bench "$G/before/spirv" ;;
    sky-bench+*)  # the current renderer with more options, commas for spaces (a knob's cost, same call)
      extra=${run#sky-bench+}; skyBench "-${extra//[^a-z0-9]/}" $BENCH "$SKY_SPIRV_DIR" ${extra//,/ } ;;
    sky-bench-before+*)  # the same with the earlier tree
      extra=${run#sky-bench-before+}
      skyBench "-before-${extra//[^a-z0-9]/}" /tmp/build-before/skyservice/sky-bench "$G/before/spirv" ${extra//,/ } ;;
    sky-bench@*)  # the current renderer with the shaders of .gpu/spirv-NAME (a shader-only variant, same call);
                  # sky-bench@NAME+OPTIONS with more options as above
      spec=${run#sky-bench@}; name=${spec%%+*}; extra=""
      [[ $spec == *+* ]] && extra=${spec#*+}
      skyBench "-$name${extra//[^a-z0-9]/}" $BENCH "$G/spirv-$name" ${extra//,/ } ;;
    baseline)  # GPU.md's yardstick at the same size, in the same call
      if timeout 60 cmake -S $G/baseline -B /tmp/bb -DCMAKE_BUILD_TYPE=Release \
           -DCLOUDPROBE_SPV=$G/baseline/cloud.comp.spv -DVulkan_INCLUDE_DIR=$G/include \
           -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 > /tmp/bcfg.log 2>&1 &&
         timeout 60 cmake --build /tmp/bb -j16 > /tmp/bbuild.log 2>&1; then
        el "baseline 1920x1080"
        timeout 120 /tmp/bb/cloudprobe --spv $G/baseline/cloud.comp.spv --width 1920 --height 1080 --frames 100 \
          --out /tmp/base-1920x1080 2>&1 | tee "$OUT/baseline.txt" | grep -i "using device\|FULL\|1/16\|timestamp"
      else
        el "baseline build FAILED"; tail -20 /tmp/bcfg.log /tmp/bbuild.log
      fi ;;
    *) el "unknown run $run (SKY_SVC_RUNS)" ;;
  esac
done
kill $CLK
el "done"
