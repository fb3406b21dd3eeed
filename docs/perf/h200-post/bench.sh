#!/usr/bin/env bash
# vksky post chain on an NVIDIA H200 (the same script as ../h100-post3, main after all merges):
# --bench 60 per-pass medians, 720p/1080p/2160p, the fill floor in the same run, medium
# compute and fragment, the default (auto), cpu; 1080p repeated 3x; a validation-clean default render and bench.
source .gpu/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $O/gpu.txt 2>&1
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for size in 1280x720 1920x1080 3840x2160; do
  w=${size%x*}; h=${size#*x}
  b="vksky --bench 60 --width $w --height $h"
  $b --sky-mode fill --sky-pass compute --post-pass compute --no-bloom > $O/fill_$size.txt 2>&1
  $b --quality medium --post-pass compute > $O/medium_compute_$size.txt 2>&1
  $b --quality medium --post-pass fragment > $O/medium_fragment_$size.txt 2>&1
  $b > $O/default_$size.txt 2>&1
  $b --quality cpu > $O/cpu_$size.txt 2>&1
done
for r in 2 3; do
  b="vksky --bench 60 --width 1920 --height 1080"
  $b --sky-mode fill --sky-pass compute --post-pass compute --no-bloom > $O/fill_1920x1080_r$r.txt 2>&1
  $b --quality medium --post-pass compute > $O/medium_compute_1920x1080_r$r.txt 2>&1
  $b > $O/default_1920x1080_r$r.txt 2>&1
done
V=$O/validate.txt; : > $V
for a in "" "--quality cpu"; do vksky --validate $a --render $O/v.exr >> $V 2>&1; echo "[$a] rc=$?" >> $V; done
vksky --validate --bench 5 --width 1920 --height 1080 >> $V 2>&1; echo "[bench default] rc=$?" >> $V
rm -f $O/*.exr
echo done > $O/done.txt
cd $O && tar czf /tmp/all.tgz *.txt && rm -f *.txt && mv /tmp/all.tgz $O/all.tgz
