#!/usr/bin/env bash
# tools/tradeoff on an NVIDIA H100 with the new model: the table --quality auto and --max-error read
# (src/app/quality_table.h) and the CSV of every configuration (docs/data/tradeoff_h100_penumbra.csv); meanwhile
# the twilight half of the README's sunset strip on the host's CPUs (niced; strip.sh renders the other half).
source .gpu/env.sh
set -u
O=$OUT
(nice -n 19 timeout 570 sunset_strip $O/sunset_strip_twilight.png --width 320 --height 64 --samples 6000 \
  --threads 14 --suns -2,-4 > $O/sunset_strip_twilight.log 2>&1; echo "rc=$?" >> $O/sunset_strip_twilight.log) &
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt 2>&1
timeout 560 tradeoff --emit-table $O/quality_table.h --csv $O/tradeoff.csv > $O/tradeoff.log 2>&1
echo "tradeoff rc=$?" >> $O/tradeoff.log
wait
