#!/usr/bin/env bash
# Issue 17's second-bounce moments on an NVIDIA H100: the cost of the model change per preset (vksky-base = the
# build before it, vksky = after; alternated, two rounds, --bench 60 per-pass medians at 1920x1080, noon / sunset /
# twilight) and a validated twilight render; meanwhile, on the host's CPUs, the README's sunset strip
# (tools/sunset_strip, niced). tools/tradeoff's table with the new model runs on its own: tradeoff.sh.
source .gpu/env.sh
set -u
O=$OUT
(nice -n 19 timeout 560 sunset_strip $O/sunset_strip.png --width 320 --height 64 --samples 6000 --threads 15 \
  > $O/sunset_strip.log 2>&1; echo "sunset_strip rc=$?" >> $O/sunset_strip.log) &
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt 2>&1
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for round in 1 2; do
  for q in low medium high ultra lesson cpu auto; do
    for sun in 70 2 -4; do
      for bin in vksky-base vksky; do
        $bin --bench 60 --width 1920 --height 1080 --quality $q --sun-elevation $sun --pitch 10 \
          > $O/bench_${bin}_${q}_${sun}_r$round.txt 2>&1
      done
    done
  done
done
V=$O/validate.txt; : > $V
for q in ultra auto; do vksky --validate --quality $q --sun-elevation -4 --render $O/v.exr >> $V 2>&1; echo "[$q] rc=$?" >> $V; done
rm -f $O/*.exr
(cd $O && tar czf /tmp/bench.tgz bench_*.txt && rm -f bench_*.txt && mv /tmp/bench.tgz $O/bench.tgz)
wait
