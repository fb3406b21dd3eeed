#!/usr/bin/env bash
# tools/compare_composite.sh OLD_VKSKY NEW_VKSKY GEN_COMPOSITE_SCENE: the composite's cases rendered by two builds and
# compared (issue 25's `--composite` through include/vksky.h must not change a pixel or a trace line): every layer of
# every EXR bit for bit (OpenImageIO; the headers record the output path), stdout (the traces, bench lines without
# their times) and stderr line for line. Cases: a generated 480x270 scene from its multilayer file, from two files
# with flags, by depth, --aerial-perspective volume, --max-error, bands of 16 rows, VKSKY_FRAMES=2, --async-luts on
# one queue, --bench, and --aovs (with the volume). Validation on in every render.
# Exit 0: all identical; 1: some output differs (listed); 2: usage.
set -u
OLD=${1:?usage: compare_composite.sh OLD_VKSKY NEW_VKSKY GEN_COMPOSITE_SCENE}
NEW=${2:?usage: compare_composite.sh OLD_VKSKY NEW_VKSKY GEN_COMPOSITE_SCENE}
GEN=${3:?usage: compare_composite.sh OLD_VKSKY NEW_VKSKY GEN_COMPOSITE_SCENE}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
S=$work/scene E=$work/edges
mkdir -p "$S" "$E" "$work/old" "$work/new"
"$GEN" "$S" 480 270 >/dev/null && "$GEN" "$E" 120 66 edges >/dev/null || { echo "gen_composite_scene failed"; exit 2; }
read -r -a CAMERA <"$S/camera.txt"
SUN="--sun-elevation 20 --sun-azimuth -60"
cases=(
  "multilayer||--composite $S/render.exr $SUN --trace-barriers --trace-passes"
  "two_files||--composite $S/beauty.exr --position $S/position.exr ${CAMERA[*]} $SUN"
  "depth||--composite $E/depth.exr $SUN --trace-barriers"
  "volume||--composite $S/render.exr $SUN --aerial-perspective volume --ap-volume-size 16x16x16 --trace-barriers"
  "max_error||--composite $S/render.exr $SUN --max-error 0.05"
  "bands|VKSKY_COMPOSITE_BAND_ROWS=16|--composite $S/render.exr $SUN --trace-barriers"
  "frames|VKSKY_FRAMES=2|--composite $S/render.exr $SUN --trace-barriers"
  "async|VKSKY_ASYNC_ONE_QUEUE=1|--composite $S/render.exr $SUN --async-luts --trace-barriers"
  "bench||--composite $S/render.exr $SUN --bench 3"
  "aovs||--aovs --width 64 --height 36 --quality lesson --trace-barriers --trace-passes"
  "aovs_frames|VKSKY_FRAMES=2|--aovs --width 64 --height 36 --quality lesson --trace-barriers"
  "aovs_volume||--aovs --width 64 --height 64 --quality lesson --aerial-perspective volume --ap-volume-size 8x8x8 --trace-barriers"
)
for c in "${cases[@]}"; do
  IFS='|' read -r name envs args <<<"$c"
  for side in old new; do
    bin=$OLD; [ $side = new ] && bin=$NEW
    # shellcheck disable=SC2086
    env $envs "$bin" $args --render "$work/$side/$name.exr" --validate >"$work/$side/$name.stdout" \
      2>"$work/$side/$name.stderr"
    echo "exit $?" >>"$work/$side/$name.stderr"
  done
done
same_pixels() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys
import OpenImageIO as oiio
def layers(path):
    out, i = [], 0
    while True:
        b = oiio.ImageBuf(path, i, 0)
        if b.has_error or b.spec().width == 0: break
        out.append((b.spec().width, b.spec().height, tuple(b.spec().channelnames), str(b.spec().format),
                    b.get_pixels(oiio.FLOAT).tobytes()))
        i += 1
    return out
a, b = layers(sys.argv[1]), layers(sys.argv[2])
sys.exit(0 if a and a == b else 1)
PY
}
fail=0
for f in "$work"/old/*; do
  b=$(basename "$f") g=$work/new/$(basename "$f")
  case $b in
    *.stdout) cmp -s <(grep -v -E 'ms|time' "$f") <(grep -v -E 'ms|time' "$g") ;;
    *.exr) same_pixels "$f" "$g" ;;
    *) cmp -s "$f" "$g" ;;
  esac || { echo "DIFFERS: $b"; diff "$f" "$g" 2>/dev/null | head -6; fail=1; }
done
[ $fail -eq 0 ] && echo "compare_composite: all $(ls "$work"/old | wc -l) outputs identical"
exit $fail
