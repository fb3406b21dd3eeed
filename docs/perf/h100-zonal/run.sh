#!/usr/bin/env bash
# Issue 17's zonal moments on an NVIDIA H100: tools/tradeoff with the new model (the table --quality auto and
# --max-error read, src/app/quality_table.h, and docs/data/tradeoff_h100_penumbra.csv); then the cost of the zonal
# moments, the build before them (0393070, vksky-before) against this one (vksky), alternated, --bench 60 per-pass
# medians at 1920x1080 for every preset, noon / sunset / twilight; and one validated render.
source .gpu/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt 2>&1
timeout 420 tradeoff --emit-table $O/quality_table.h --csv $O/tradeoff.csv > $O/tradeoff.log 2>&1
echo "tradeoff rc=$?" >> $O/tradeoff.log
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for q in low medium high ultra lesson cpu; do
  for sun in 70 2 -4; do
    for b in vksky-before vksky; do
      $b --bench 60 --width 1920 --height 1080 --quality $q --sun-elevation $sun --pitch 10 \
        > $O/bench_${b}_${q}_${sun}.txt 2>&1
    done
  done
done
vksky --validate --quality ultra --sun-elevation 2 --render $O/v.exr > $O/validate.txt 2>&1; echo "rc=$?" >> $O/validate.txt
rm -f $O/v.exr
(cd $O && tar czf /tmp/bench.tgz bench_*.txt && rm -f bench_*.txt && mv /tmp/bench.tgz $O/bench.tgz)
