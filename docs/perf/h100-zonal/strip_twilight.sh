#!/usr/bin/env bash
# The twilight half of the README's sunset strip (tools/sunset_strip) on the H100 host's 16 CPUs.
source .gpu/env.sh
set -u
timeout 580 sunset_strip $OUT/sunset_strip_twilight.png --width 320 --height 64 --samples 6000 --threads 16 \
  --suns -2,-4 > $OUT/sunset_strip_twilight.log 2>&1
echo "rc=$?" >> $OUT/sunset_strip_twilight.log
