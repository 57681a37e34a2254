#!/usr/bin/env bash
# Command-line tests of sky-ingest (exit codes of README "sky-ingest", no partial output on failure).
# usage: cli_test.sh CASE SKY_INGEST SHARED_DIR WORK_DIR    (exit 77 = skipped)
set -u
case_name=$1; tool=$2; shared=$3; work=$4/$1
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
gfs=$shared/weather/gfs-2p5deg-20110110-12z-f120.grib2
wrf=$shared/weather/wrf-katrina-d02-20050828.nc

fail() { echo "FAIL: $*"; exit 1; }
need() { [ -f "$1" ] || { echo "SKIP: $1 not found"; exit 77; }; }
# expect CODE cmd...: runs cmd, checks its exit code, keeps stdout/stderr in out.txt/err.txt
expect() { local want=$1; shift; "$@" >out.txt 2>err.txt; local got=$?; cat out.txt err.txt;
           [ "$got" -eq "$want" ] || fail "exit code $got, expected $want: $*"; }
contains() { grep -q -- "$2" "$1" || fail "'$2' not in $1"; }
no_output() { [ ! -e "$1" ] || fail "partial output $1 left behind"; ls -a | grep -q '\.tmp\.' && fail "temp file left"; return 0; }

case $case_name in
info-gfs)
  need "$gfs"
  expect 0 "$tool" info "$gfs"
  contains out.txt "GRIB2 (343 messages)"
  contains out.txt "tcc/lowCloudLayer"
  contains out.txt "gh/isobaricInhPa .*26 levels"
  contains out.txt "2011-01-15T12:00:00Z"
  contains out.txt "not found";;
info-wrf)
  need "$wrf"
  expect 0 "$tool" info --rules "$wrf"
  contains out.txt "WRF, 48 x 48 columns, 14 levels"
  contains out.txt "2005-08-28_21:00:00"
  contains out.txt "QCLOUD"
  contains out.txt "Cumulonimbus";;
convert-gfs)
  need "$gfs"
  expect 0 "$tool" convert "$gfs" -o gfs.skywx
  contains out.txt "1 snapshot(s), 144 x 73"
  expect 0 "$tool" check gfs.skywx
  contains out.txt "valid snapshot file"
  expect 0 "$tool" convert --quiet "$gfs" -o quiet.skywx
  [ -s out.txt ] && fail "--quiet printed something"
  cmp -s gfs.skywx quiet.skywx || fail "conversion is not deterministic";;
convert-wrf)
  need "$wrf"
  expect 0 "$tool" convert "$wrf" -o wrf.skywx
  expect 0 "$tool" check wrf.skywx
  contains out.txt "4 snapshot(s)"
  contains out.txt "2005-08-28T21:00:00Z";;
empty)
  : > empty.grib2
  expect 4 "$tool" convert empty.grib2 -o out.skywx
  contains err.txt "empty file"
  no_output out.skywx;;
png)
  printf '\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10' > image.grib2
  expect 4 "$tool" convert image.grib2 -o out.skywx
  contains err.txt "PNG"
  no_output out.skywx;;
truncated)
  need "$gfs"
  head -c 1800000 "$gfs" > cut.grib2
  echo keep > out.skywx
  expect 5 "$tool" convert cut.grib2 -o out.skywx
  contains err.txt "message 159"
  contains err.txt "truncated"
  [ "$(cat out.skywx)" = keep ] || fail "existing output was touched";;
netcdf-unrelated)
  # A valid NetCDF-3 classic file with no dimensions and no variables (32-byte header).
  printf 'CDF\x01\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0' > none.nc
  expect 7 "$tool" convert none.nc -o out.skywx
  contains err.txt "none of the variables"
  no_output out.skywx;;
missing)
  expect 3 "$tool" convert /nonexistent/x.grib2 -o out.skywx
  no_output out.skywx;;
usage)
  expect 2 "$tool"
  expect 2 "$tool" convert x.grib2
  expect 2 "$tool" frobnicate
  expect 0 "$tool" --help
  contains out.txt "Exit codes";;
check-bad)
  need "$wrf"
  expect 0 "$tool" convert --quiet "$wrf" -o good.skywx
  size=$(stat -c %s good.skywx)
  head -c $((size - 10)) good.skywx > cut.skywx
  expect 5 "$tool" check cut.skywx
  contains err.txt "truncated"
  cp good.skywx flip.skywx
  printf '\x55' | dd of=flip.skywx bs=1 seek=$((size - 100)) conv=notrunc status=none
  expect 5 "$tool" check flip.skywx
  contains err.txt "checksum"
  expect 5 "$tool" check "$wrf"
  contains err.txt "not a weather snapshot"
  expect 5 "$tool" check /nonexistent.skywx;;
*) fail "unknown case $case_name";;
esac
echo PASS
