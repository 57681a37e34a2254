#!/bin/bash
# sky-bench option sets A/B on the GPU machine, each scene in its own run and the option sets taking
# turns within each scene (BENCHMARKS.md). A GPU may idle its clock down in
# long runs of short frames; runs this short keep it at its full clock.
# Usage on the device (carry [".gl", ".gpu"], after device_prepare.sh):
#   VARIANTS=" ;--cone-tail-reuse 0" bash skyservice/bench/device_variants.sh
# VARIANTS: option sets separated by ';' (a blank one: the defaults). SCENES (default: all eight),
# SIZES (default 1920x1080; reprojected mode, 100 frames after 20 warm-up), FULL_SIZES (default 1920x1080:
# all scenes in full mode, 4 GPU frames per sample, each option set; empty: none), BUILD (a folder with
# sky-bench and spirv/; default .gpu/prebuilt with .gpu/spirv), SPIRVS (optional: one SPIR-V folder per
# option set, separated by ';', for A/B of shader builds; blank entries keep BUILD's). Everything lands in
# $OUT/r.tgz; the tables (median total ms per scene and option set), the baseline at each size and the
# clock check are printed.
set -u
G=$PWD/.gpu; P=/tmp/deps; R=/tmp/r; mkdir -p $R $P
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
for f in "$G"/debs/*.deb; do dpkg -x "$f" $P; done
export LD_LIBRARY_PATH=$P/usr/lib/x86_64-linux-gnu
if [ -n "${BUILD:-}" ]; then BENCH=$BUILD/sky-bench; export SKY_SPIRV_DIR=$BUILD/spirv
else BENCH=$G/prebuilt/sky-bench; export SKY_SPIRV_DIR=$G/spirv; fi
$BENCH --scene clear --width 64 --height 64 --frames 1 --warmup 0 --device NVIDIA > /dev/null 2>&1 ||
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=timestamp,clocks.sm --format=csv,noheader -lms 200 > $R/clocks.csv 2>/dev/null &
CLK=$!
IFS=';' read -ra VARS <<< "${VARIANTS:- }"
IFS=';' read -ra SPVS <<< "${SPIRVS:-}"
spirv_of() { local d=${SPVS[$1]:-}; d=${d// /}; echo "${d:-$SKY_SPIRV_DIR}"; }
ALL="clear scattered-cumulus stratocumulus-deck cumulonimbus cirrus-only inside-cloud above-deck-FL350 sunset"
for size in ${SIZES:-1920x1080}; do
  for sc in ${SCENES:-$ALL}; do
    for i in "${!VARS[@]}"; do
      # shellcheck disable=SC2086
      SKY_SPIRV_DIR=$(spirv_of $i) timeout 90 $BENCH --scene $sc --width ${size%x*} --height ${size#*x} \
        --frames 100 --warmup 20 --mode reprojected --device NVIDIA --json $R/rep-$size-$sc-v$i.json \
        ${VARS[$i]} > $R/rep-$size-$sc-v$i.txt 2>&1
    done
  done
done
for size in ${FULL_SIZES-1920x1080}; do
  for i in "${!VARS[@]}"; do
    # shellcheck disable=SC2086
    SKY_SPIRV_DIR=$(spirv_of $i) timeout 150 $BENCH --scene all --width ${size%x*} --height ${size#*x} \
      --frames 100 --warmup 10 --gpu-frames 4 --device NVIDIA --json $R/full-$size-v$i.json \
      ${VARS[$i]} > $R/full-$size-v$i.txt 2>&1
  done
done
kill $CLK
cmake -S $G/baseline -B /tmp/bb -DCMAKE_BUILD_TYPE=Release -DCLOUDPROBE_SPV=$G/baseline/cloud.comp.spv \
  -DVulkan_INCLUDE_DIR=$G/include -DVulkan_LIBRARY=/usr/lib/x86_64-linux-gnu/libvulkan.so.1 > /dev/null 2>&1 &&
  cmake --build /tmp/bb -j16 > /dev/null 2>&1 && PROBE=/tmp/bb/cloudprobe || PROBE=$G/prebuilt/cloudprobe
for size in $(echo ${SIZES:-1920x1080} ${FULL_SIZES-1920x1080} | tr ' ' '\n' | sort -u); do
  echo "baseline $size" >> $R/baseline.txt
  timeout 120 $PROBE --spv $G/baseline/cloud.comp.spv --width ${size%x*} --height ${size#*x} --frames 100 --out /tmp/base \
    2>&1 | grep "FULL\|1/16 (" >> $R/baseline.txt
done
tar czf $OUT/r.tgz -C $R .
echo "option sets: $(for i in "${!VARS[@]}"; do printf 'v%d=[%s] ' $i "${VARS[$i]}"; done)"
python3 - $R <<'PY'
import glob, json, os, sys
R = sys.argv[1]
def medians(path):
    try:
        doc = json.load(open(path))
    except (OSError, ValueError):
        return {}, None
    return {s['name']: s['gpuMs'].get('total', {}).get('median') for s in doc['scenes']}, doc.get('memory', {}).get('totalBytes')
tables = {}
for f in sorted(glob.glob(R + '/*.json')):
    name = os.path.basename(f)[:-5]
    kind, rest = name.split('-', 1)
    size, rest = rest.split('-', 1)
    scene, v = (rest.rsplit('-', 1) if kind == 'rep' else ('all', rest))
    meds, mem = medians(f)
    for sc, ms in meds.items():
        tables.setdefault((kind, size), {}).setdefault(sc, {})[v] = ms
        if mem and v == 'v0':
            tables[(kind, size)].setdefault('memory bytes', {})[v] = mem
for (kind, size), rows in sorted(tables.items()):
    vs = sorted({v for r in rows.values() for v in r})
    print('== %s %s, median total GPU ms' % ('reprojected' if kind == 'rep' else 'full', size))
    print('%-20s' % 'scene' + ''.join('%12s' % v for v in vs))
    for sc, r in rows.items():
        print('%-20s' % sc + ''.join('%12s' % (('%.3f' % r[v]) if sc != 'memory bytes' else str(r[v])) if r.get(v) else '%12s' % '-' for v in vs))
PY
cat $R/baseline.txt
awk -F', ' '{split($2, a, " "); if (a[1] < 1700) low++; n++} END {print "SM clock samples", n, "below 1700 MHz:", low + 0}' $R/clocks.csv
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
