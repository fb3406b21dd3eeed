#!/usr/bin/env bash
# The model change's cost on lavapipe (2 cores, 1280x720): vksky-base (before) and vksky (after) alternated,
# two rounds, --bench 10 per preset at noon (70) and twilight (-4). Usage: lavapipe.sh BASE NEW OUTDIR
set -u
B=$1 N=$2 O=$3
for round in 1 2; do
  for q in cpu low medium lesson; do
    for sun in 70 -4; do
      for bin in base new; do
        exe=$B; [ $bin = new ] && exe=$N
        $exe --bench 10 --width 1280 --height 720 --quality $q --sun-elevation $sun --pitch 10 \
          > $O/lp_${bin}_${q}_${sun}_r$round.txt 2>&1
      done
    done
  done
done
