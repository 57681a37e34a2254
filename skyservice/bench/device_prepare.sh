#!/bin/bash
# Prepares the folders that travel to the GPU machine with the device tool's `carry` (GPU.md): run on the
# dev machine from the repo root. Both folders are ignored by git (.gitignore).
#   .gl/   the Vulkan loader and glvnd as Debian .debs (the GPU machine has none)
#   .gpu/  Vulkan C headers, the SPIR-V (the GPU machine has no glslang), the build dependencies of
#          sky_renderer as .debs, the baseline's sources and SPIR-V, and fallback binaries built here.
# Needs: the build folder below configured and built (sky-bench), and ../shared/baseline.
set -eu
BUILD=${1:-build-bench}
SHARED=${SKY_SHARED_DIR:-$PWD/../shared}
cmake --build "$BUILD" --target sky-bench -j2
rm -rf .gl .gpu
mkdir -p .gl .gpu/debs .gpu/include .gpu/baseline .gpu/prebuilt
(cd .gl && apt-get download libvulkan1 libglvnd0 libegl1 libgl1 libglx0 libopengl0)
(cd .gpu/debs && apt-get download libgeographiclib-dev libgeographiclib23 libopenexr-dev libopenexr-3-1-30 \
    libimath-dev libimath-3-1-29 libpng-dev libpng16-16 zlib1g-dev zlib1g libglm-dev nlohmann-json3-dev \
    libcli11-dev pkgconf pkgconf-bin libpkgconf3)
for f in .gpu/debs/*%3a*; do [ -e "$f" ] && mv "$f" "${f//%3a/_}"; done
cp -r /usr/include/vulkan /usr/include/vk_video .gpu/include/ && rm -f .gpu/include/vulkan/*.hpp
cp -r "$BUILD/spirv" .gpu/spirv
cmake -S "$SHARED/baseline" -B "$BUILD/baseline" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$BUILD/baseline" -j2
cp "$SHARED"/baseline/{CMakeLists.txt,cloudprobe.cpp,cloud.comp} "$BUILD/baseline/cloud.comp.spv" .gpu/baseline/
strip -o .gpu/prebuilt/sky-bench "$BUILD/skyservice/sky-bench"
strip -o .gpu/prebuilt/cloudprobe "$BUILD/baseline/cloudprobe"
# Optional builds for device_run.sh's builds mode: SKY_BENCH_BUILDS="label=DIR ...", each DIR holding a
# sky-bench and its spirv/ (copied out of a build folder, e.g. of the main branch).
for b in ${SKY_BENCH_BUILDS:-}; do
  mkdir -p ".gpu/builds/${b%%=*}"
  strip -o ".gpu/builds/${b%%=*}/sky-bench" "${b#*=}/sky-bench"
  cp -r "${b#*=}/spirv" ".gpu/builds/${b%%=*}/spirv"
done
du -sh .gl .gpu
