#!/usr/bin/env bash
# vksky post chain after the layout split and the class-aware upsample (branch post, second H100 run): per-pass
# medians of --bench 60 (60 frames after warm-up), 720p/1080p/2160p, the fill floor in the same run, medium
# (compute and fragment post), the default (--quality auto), lesson, cpu; 1080p repeated 3x (spread); then
# validation-clean renders, compute vs fragment post, the upsample check and a tiny size on the GPU.
source .gpu-post/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $O/gpu.txt 2>&1
vksky --list-devices > $O/devices.txt 2>&1
vksky --dump-scene | grep -A3 skyview_lut > $O/auto_choice.txt 2>&1     # what --quality auto picks here
vksky --bench 300 --width 3840 --height 2160 --quality lesson > /dev/null 2>&1   # clocks up
for size in 1280x720 1920x1080 3840x2160; do
  w=${size%x*}; h=${size#*x}
  b="vksky --bench 60 --width $w --height $h"
  $b --sky-mode fill --sky-pass compute --post-pass compute --no-bloom > $O/fill_$size.txt 2>&1
  $b --quality medium --post-pass compute > $O/medium_compute_$size.txt 2>&1
  $b --quality medium --post-pass fragment > $O/medium_fragment_$size.txt 2>&1
  $b > $O/default_$size.txt 2>&1
  $b --quality lesson --post-pass compute > $O/lesson_compute_$size.txt 2>&1
  $b --quality cpu > $O/cpu_$size.txt 2>&1
done
for r in 2 3; do
  b="vksky --bench 60 --width 1920 --height 1080"
  $b --sky-mode fill --sky-pass compute --post-pass compute --no-bloom > $O/fill_1920x1080_r$r.txt 2>&1
  $b --quality medium --post-pass compute > $O/medium_compute_1920x1080_r$r.txt 2>&1
  $b > $O/default_1920x1080_r$r.txt 2>&1
done
# validation (+ sync validation): the default and cpu renders, compute and fragment post, a tiny size
V=$O/validate.txt; : > $V
for a in "" "--quality cpu --post-pass compute" "--quality cpu --post-pass fragment" "--width 1 --height 1" "--width 7 --height 3 --quality cpu"; do
  vksky --validate $a --render $O/v.exr >> $V 2>&1; echo "[$a] rc=$?" >> $V
done
vksky --validate --bench 5 --width 1920 --height 1080 >> $V 2>&1; echo "[bench default] rc=$?" >> $V
# compute vs fragment post (1080p sunset, lesson: the sun's bloom), as tests/post_compare_test.sh bounds it
for pp in fragment compute; do
  vksky --validate --post-pass $pp --width 1920 --height 1080 --sun-elevation 3 --quality lesson --render $O/c_$pp.exr --render $O/c_$pp.png >> $V 2>&1; echo "[compare $pp] rc=$?" >> $V
  vksky --validate --post-pass $pp --width 1920 --height 1080 --sun-elevation 3 --quality lesson --no-bloom --render $O/c_$pp-nb.exr >> $V 2>&1; echo "[compare $pp nb] rc=$?" >> $V
done
post_compare $O/c_fragment.exr $O/c_compute.exr $O/c_fragment-nb.exr $O/c_compute-nb.exr $O/c_fragment.png $O/c_compute.png 0.02 0.02 2 0.25 > $O/compare_1920x1080.txt 2>&1; echo "rc=$?" >> $O/compare_1920x1080.txt
# the class-aware upsample (tests/upsample_edges_test.sh's cases)
for s in 0.5 1; do
  vksky --validate --no-bloom --no-sun-disc --width 160 --height 90 --sun-elevation 3 --pitch 0 --fov 12 --quality cpu --render-scale $s --render $O/u$s.exr >> $V 2>&1
  vksky --validate --no-bloom --no-sun-disc --width 161 --height 91 --altitude 10 --pitch -5 --fov 40 --sun-elevation 40 --quality cpu --post-pass compute --render-scale $s --render $O/h$s.exr >> $V 2>&1
done
{ upsample_edges $O/u0.5.exr $O/u1.exr 0.05; echo "rc=$?"; upsample_edges $O/h0.5.exr $O/h1.exr 0.05; echo "rc=$?"; } > $O/upsample.txt 2>&1
rm -f $O/*.exr $O/*.png
echo done > $O/done.txt
# the device tool returns a few files only: one archive
cd $O && tar czf /tmp/all.tgz *.txt && rm -f *.txt && mv /tmp/all.tgz $O/all.tgz
