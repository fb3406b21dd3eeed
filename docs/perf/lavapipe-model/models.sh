#!/usr/bin/env bash
# lavapipe (2 cores, 1280x720): the lesson's model (--sun-visibility lesson-fade) vs the new one (penumbra) in one
# build, alternated, two rounds, --bench 10, noon (70) and twilight (-4). Usage: models.sh VKSKY OUTDIR
set -u
X=$1 O=$2
for round in 1 2; do
  for q in cpu medium lesson; do
    for sun in 70 -4; do
      for m in lesson-fade penumbra; do
        $X --bench 10 --width 1280 --height 720 --quality $q --sun-elevation $sun --pitch 10 --sun-visibility $m \
          > $O/lpm_${m}_${q}_${sun}_r$round.txt 2>&1
      done
    done
  done
done
