# Sourced by a test that renders many images with the same LUT settings and whose checks are about something else
# (sizes, render scales, presets): `own_lut_cache DIR` turns vksky's LUT cache on (sky/lut_cache.h) in a cache
# directory of the test's own, DIR/xdg. The suite turns the cache off (tests/CMakeLists.txt: tests count LUT passes
# and trace barriers in one shared directory); here the first render of each LUT setting still computes its LUTs
# under validation and synchronization validation, as every render did, and the later ones upload them (the
# lut_cache_upload pass, validated the same way) instead of computing the same LUTs again: size_edges went from 147 s
# to 48 s of CPU on lavapipe (issue 27 item 5). The pixels are the same either way (ctest lut_cache: a hit's image
# equals a miss's). The suite's Mesa shader cache and validation cache are linked in, so that compiling is shared.
own_lut_cache() {
    local dir=$1/xdg shared=${XDG_CACHE_HOME:-}
    mkdir -p "$dir/vksky"
    if [ -n "$shared" ] && [ -d "$shared" ]; then
        [ -d "$shared/mesa_shader_cache" ] && ln -s "$shared/mesa_shader_cache" "$dir/mesa_shader_cache"
        [ -f "$shared/shader_validation_cache-0.bin" ] && cp "$shared/shader_validation_cache-0.bin" "$dir/"
        cp "$shared"/vksky/pipelines-*.bin "$dir/vksky/" 2>/dev/null
    fi
    export XDG_CACHE_HOME=$dir VKSKY_LUT_CACHE=1
}
