#!/usr/bin/env bash
# The long-history rows of docs/performance.md (#28), whole process: generates a displacement
# history (a two-sine, 1.5 Hz 2 mm plus 23 Hz 0.1 mm, written as a rig writes it: time
# shortest, displacement to 1 nm; the input of bench/stream_bench.cpp, byte for byte at 10 kHz)
# and runs specimen D (examples/specimen_d.rheo) over it with `rheo simulate`, CSV in and out,
# under /usr/bin/time -v (Debian's `time` package): wall and CPU time, peak memory (maximum
# resident set).
#
#   bench/long_history.sh [--rows N] [--rate HZ] [--runs K] [--elements] [--hdf5] [--report-data] [--fit-data] [--fit-shape] [--rheo PATH]
#
# --hdf5: HDF5 in and out instead (docs/data-formats.md, "HDF5 files"): the input is the CSV
# history simulated once by rheo into history-N-HZ.h5 (kept; rheo's result holds /time and
# /displacement, its default layout), the output out.h5.
#
# --report-data: `rheo report` of specimen D against a measured history instead, read as fits
# and reports read their data: the model's own result over the CSV history (time, displacement,
# force), simulated once into history-N-HZ-measured.csv (kept), the output report.html.
#
# --fit-data: `rheo fit` of a spring (`spring e (k = 300 N/mm in [1, 10000])`) to that measured
# history instead: --max-evaluations 3, the fitted model written to fitted.rheo (a separable
# solve and its standard errors: what a fit holds for a long history, docs/performance.md).
#
# --fit-shape: the same with no force scale free, so the plain Levenberg-Marquardt search runs
# (a Maxwell time and a yield force free, every stiffness held; --max-evaluations 30): its
# differenced Jacobians are formed as the samples stream past (runtime/fit/history_jacobian.hpp).
#
# Defaults: 1e7 rows at 10 kHz, 3 runs, build/rheo. The 24 h durability log of #28 is
# `--rows 86400000 --rate 1000`. Input and output go to ${TMPDIR:-/tmp}/rheo-bench-history/
# (history-N-HZ.csv, generated once and kept; out.csv, removed at the end); N rows at 10 kHz
# take about 19 bytes each in and 37 out, so the 1e7 rows need 0.6 GB free there.
set -euo pipefail
cd "$(dirname "$0")/.."
rows=10000000 rate=10000 runs=3 rheo=build/rheo elements=() format=csv
while [ $# -gt 0 ]; do
  case $1 in
    --rows) rows=$2; shift 2 ;;
    --rate) rate=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --rheo) rheo=$2; shift 2 ;;
    --elements) elements=(--elements); shift ;;
    --hdf5) format=h5; shift ;;
    --report-data) format=report; shift ;;
    --fit-data) format=fit; shift ;;
    --fit-shape) format=fit-shape; shift ;;
    -h|--help) sed -n '2,30p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench/long_history.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x /usr/bin/time ] || { echo "bench/long_history.sh: needs /usr/bin/time (Debian package 'time')" >&2; exit 2; }
[ -x "$rheo" ] || { echo "bench/long_history.sh: no rheo binary at $rheo; build it first (README)" >&2; exit 2; }

dir=${TMPDIR:-/tmp}/rheo-bench-history
mkdir -p "$dir"
csv=$dir/history-$rows-$rate.csv
trap 'rm -f "$csv.tmp"' EXIT  # an interrupted generation leaves no partial file
if [ ! -e "$csv" ]; then
  echo "generating $csv ($rows rows at $rate Hz)" >&2
  # As bench/stream_bench.cpp writes it: t = k / rate shortest (%.10g is exact for these
  # times), u = 2 sin(2 pi 1.5 t) + 0.1 sin(2 pi 23 t) to 6 decimals; pi = atan2(0, -1).
  awk -v rows="$rows" -v rate="$rate" 'BEGIN {
    pi = atan2(0, -1)
    print "time [s],displacement [mm]"
    for (k = 0; k < rows; ++k) {
      t = k / rate
      printf "%.10g,%.6f\n", t, 2.0 * sin(2 * pi * 1.5 * t) + 0.1 * sin(2 * pi * 23.0 * t)
    }
  }' >"$csv.tmp"
  mv "$csv.tmp" "$csv"
fi
model=$dir/history-$rows-$rate.rheo
input=$csv
if [ "$format" = h5 ]; then
  input=$dir/history-$rows-$rate.h5
  if [ ! -e "$input" ]; then
    echo "converting $csv to $input (rheo simulate, CSV in, HDF5 out)" >&2
    { sed -n '/^model /,/^}/p' examples/specimen_d.rheo
      printf 'simulate {\n  history file = "%s"\n}\n' "$(basename "$csv")"; } >"$model"
    "$rheo" simulate "$model" -o "$input"
  fi
fi
if [ "$format" = report ] || [ "$format" = fit ] || [ "$format" = fit-shape ]; then
  input=$dir/history-$rows-$rate-measured.csv
  if [ ! -e "$input" ]; then
    echo "simulating $csv into $input (rheo simulate: time, displacement, force)" >&2
    { sed -n '/^model /,/^}/p' examples/specimen_d.rheo
      printf 'simulate {\n  history file = "%s"\n}\n' "$(basename "$csv")"; } >"$model"
    "$rheo" simulate "$model" -o "$input.tmp"
    mv "$input.tmp" "$input"
  fi
fi
if [ "$format" = report ]; then
  sed -n '/^model /,/^}/p' examples/specimen_d.rheo >"$model"
  command=(report "$model" --data "$input" -o "$dir/report.html") out=$dir/report.html
elif [ "$format" = fit ]; then
  model=$dir/spring.rheo
  printf 'model s {\n  spring e (k = 300 N/mm in [1, 10000])\n}\n' >"$model"
  command=(fit "$model" --data "$input" --max-evaluations 3 -o "$dir/fitted.rheo") out=$dir/fitted.rheo
elif [ "$format" = fit-shape ]; then
  model=$dir/shape.rheo
  printf 'model s {\n  spring e (k = 1000 N/mm)\n  maxwell m (k = 300 N/mm, tau = 20 ms in [0.1, 1000])\n  friction f (k = 500 N/mm, fy = 50 N in [1, 1000])\n}\n' >"$model"
  command=(fit "$model" --data "$input" --max-evaluations 30 -o "$dir/fitted.rheo") out=$dir/fitted.rheo
else
  # The model block of the example, then one history protocol over the generated file.
  { sed -n '/^model /,/^}/p' examples/specimen_d.rheo
    printf 'simulate {\n  history file = "%s"\n  output "out.%s"\n}\n' "$(basename "$input")" "$format"; } >"$model"
  command=(simulate "$model" "${elements[@]}") out=$dir/out.$format
fi

echo "rheo ${command[*]}: $(stat -c %s "$input") bytes in, $rows rows, $runs run(s)"
for ((run = 1; run <= runs; ++run)); do
  /usr/bin/time -v "$rheo" "${command[@]}" 2>"$dir/time.log" >/dev/null ||
    { cat "$dir/time.log" >&2; exit 1; }
  awk -F': ' -v out="$(stat -c %s "$out")" '
    /Elapsed \(wall clock\)/ { wall = $2 } /User time/ { user = $2 } /System time/ { sys = $2 }
    /Maximum resident set size/ { rss = $2 }
    END { printf "wall %s, CPU %.2f s (user %.2f + sys %.2f), peak memory %.1f MB, %s bytes out\n",
          wall, user + sys, user, sys, rss / 1024, out }' "$dir/time.log"
done
rm -f "$out" "$dir/time.log"
