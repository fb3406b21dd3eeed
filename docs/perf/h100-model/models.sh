#!/usr/bin/env bash
# The cost of the new model against the lesson's in one build on an NVIDIA H100: --sun-visibility lesson-fade (the
# seed's model: binary shadow x fade, isotropic Psi, no moments read; specialization constants) vs penumbra (the
# default), alternated, two rounds, --bench 60 per-pass medians at 1920x1080, noon / sunset / twilight.
source .gpu/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt 2>&1
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for round in 1 2; do
  for q in low medium high ultra lesson cpu; do
    for sun in 70 2 -4; do
      for m in lesson-fade penumbra; do
        vksky --bench 60 --width 1920 --height 1080 --quality $q --sun-elevation $sun --pitch 10 \
          --sun-visibility $m > $O/bench_${m}_${q}_${sun}_r$round.txt 2>&1
      done
    done
  done
done
vksky --quality auto --sun-elevation 70 --bench 60 --width 1920 --height 1080 --pitch 10 > $O/bench_auto_70.txt 2>&1
vksky --quality auto --sun-elevation 70 --dump-scene > $O/auto_choice_noon.json 2>&1
(cd $O && tar czf /tmp/models.tgz bench_*.txt && rm -f bench_*.txt && mv /tmp/models.tgz $O/models.tgz)
