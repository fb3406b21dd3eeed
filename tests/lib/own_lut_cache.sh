# Sourced by a test that renders many images with the same LUT settings and whose checks are about something else
# (sizes, render scales, presets): `own_lut_cache DIR` turns vksky's LUT cache on (sky/lut_cache.h) in a cache
# directory of the test's own, DIR/xdg. The suite turns the cache off (tests/CMakeLists.txt: tests count LUT passes
# and trace barriers in one shared directory); here the first render of each LUT setting still computes its LUTs
# under validation and synchronization validation, as every render did, and the later ones upload them (the
# lut_cache_upload pass, validated the same way) instead of computing the same LUTs again: size_edges went from 147 s
# to 48 s of CPU on lavapipe (issue 27 item 5). The pixels are the same either way (ctest lut_cache: a hit's image
# equals a miss's). The suite's Mesa shader cache and validation cache are linked in, so that compiling is shared.
# Under ctest these tests are in the suite's shared LUT cache (tests/CMakeLists.txt, VKSKY_SHARED_LUT_TESTS:
# VKSKY_LUT_CACHE=1 and the suite's directory): they keep it, and meet the LUTs the other tests computed (size_edges'
# --quality ultra is the Earth's ultra LUTs, which the fixture earth_ultra_luts computes once per run). The test's
# own directory is for a test run by hand, or a suite that keeps the cache off.
own_lut_cache() {
    [ "${VKSKY_LUT_CACHE:-}" = 1 ] && [ -n "${XDG_CACHE_HOME:-}" ] && return 0
    local dir=$1/xdg shared=${XDG_CACHE_HOME:-}
    mkdir -p "$dir/vksky"
    if [ -n "$shared" ] && [ -d "$shared" ]; then
        [ -d "$shared/mesa_shader_cache" ] && ln -s "$shared/mesa_shader_cache" "$dir/mesa_shader_cache"
        [ -f "$shared/shader_validation_cache-0.bin" ] && cp "$shared/shader_validation_cache-0.bin" "$dir/"
        cp "$shared"/vksky/pipelines-*.bin "$dir/vksky/" 2>/dev/null
    fi
    export XDG_CACHE_HOME=$dir VKSKY_LUT_CACHE=1
}
