#!/usr/bin/env bash
# tools/tradeoff on an NVIDIA H100 again after --quality cpu got 24 sky-view steps (a new sweep configuration,
# medium-skyview96-s24-scale0.5-bloomq): the table src/app/quality_table.h and docs/data/tradeoff_h100_penumbra.csv;
# then the default (auto) and --quality cpu frames at 1920x1080, noon and twilight, against the fill floor.
source .gpu/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv > $O/gpu.txt 2>&1
timeout 500 tradeoff --emit-table $O/quality_table.h --csv $O/tradeoff.csv > $O/tradeoff.log 2>&1
echo "tradeoff rc=$?" >> $O/tradeoff.log
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for round in 1 2; do
  for sun in 70 -4; do
    vksky --bench 60 --width 1920 --height 1080 --sun-elevation $sun --pitch 10 > $O/auto_${sun}_r$round.txt 2>&1
    vksky --bench 60 --width 1920 --height 1080 --sun-elevation $sun --pitch 10 --quality cpu > $O/cpu_${sun}_r$round.txt 2>&1
    vksky --bench 60 --width 1920 --height 1080 --sun-elevation $sun --pitch 10 --quality medium > $O/medium_${sun}_r$round.txt 2>&1
    vksky --bench 60 --width 1920 --height 1080 --sun-elevation $sun --pitch 10 --sky-mode fill --sky-pass compute \
      --no-bloom > $O/fill_${sun}_r$round.txt 2>&1
  done
done
vksky --validate --quality cpu --sun-elevation 20 --render $O/v.exr > $O/validate.txt 2>&1; echo "rc=$?" >> $O/validate.txt
rm -f $O/v.exr
