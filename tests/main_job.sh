#!/usr/bin/env bash
# The README's main job as a test: every command on its own built-in default scene, the --print-scene text read back
# by the same command, at --scale (default 0.01: the same scenes through the same code, a hundredth of the walks and
# samples), and each output the README names checked to be there. A default scene its own reader refuses, or a run
# that leaves out what it promises, fails here.
#   main_job.sh SMITHLAB WORK_DIR [SCALE]
set -euo pipefail
exe=$1 work=$2 scale=${3:-0.01}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
"$exe" check --all > check.txt
for command in report trace fit tables; do
  "$exe" "$command" --print-scene > "$command.toml"
  echo "main_job: smithlab $command $command.toml --scale $scale" >&2
  "$exe" "$command" "$command.toml" --scale "$scale" --output "$command/" > "$command.txt"
done
missing=0
for f in report/report.md report/variants.csv report/bench.json report/g2_variants.csv report/sampling.csv \
         report/walk_albedo.csv trace/albedo.csv trace/meta.json fit/report.md fit/constants.csv fit/errors.csv \
         fit/compensation.csv fit/compensation_error.csv fit/furnace.csv fit/compensation_orders.csv fit/meta.json \
         tables/report.md tables/compensation.csv tables/compensation_avg.csv tables/compensation_error.csv \
         tables/compensation_orders.csv tables/furnace_tables.csv tables/furnace.csv tables/meta.json; do
  [ -s "$f" ] || { echo "main_job: $f is missing or empty" >&2; missing=1; }
done
# The figures (report/*.png, fit/furnace.png, fit/pictures/*.png) and the tables for renderers (fit/compensation/,
# tables/compensation/).
for pattern in 'report/*.png' fit/furnace.png 'fit/pictures/*.png' 'fit/compensation/*.h' 'fit/compensation/*.glsl' \
               'fit/compensation/*.hlsl' 'fit/compensation/*.png' 'fit/compensation/*.json' tables/furnace.png \
               'tables/compensation/*.h' 'tables/compensation/*.glsl' 'tables/compensation/*.hlsl' \
               'tables/compensation/*.png' 'tables/compensation/*.json'; do
  compgen -G "$pattern" > /dev/null || { echo "main_job: nothing matches $pattern" >&2; missing=1; }
done
# The default scenes of fit and tables share their [[ndf]], [compensation] and seed: tables writes the fit's files.
for f in tables/compensation/* tables/compensation.csv tables/compensation_avg.csv tables/compensation_error.csv \
         tables/compensation_orders.csv tables/furnace_tables.csv tables/furnace.csv; do
  cmp -s "$f" "fit/${f#tables/}" || { echo "main_job: $f differs from fit/${f#tables/}" >&2; missing=1; }
done
exit $missing
