/* A quality configuration's knobs as its definition gives them (src/app/quality/quality.c), one "key value" a line in
 * the scene file's names: what a frame rendered under that configuration must record in its header's vksky:scene.
 * Reads the definitions, not a render or a header (sequences_test.sh: --max-error's printed pick against the frames).
 * Usage: quality_knobs NAME; exit 2 for a name no preset or measured configuration has. */
#include "app/quality/quality.h"
#include <stdio.h>
#include <string.h>

static const quality_config *named(const char *name)
{
    for (int i = 0; i < 4; ++i)
        if (!strcmp(quality_presets[i].name, name)) return &quality_presets[i];
    for (int i = 0; i < quality_sweep_count; ++i)
        if (!strcmp(quality_sweep[i].name, name)) return &quality_sweep[i];
    return NULL;
}

int main(int argc, char **argv)
{
    const quality_config *q = argc == 2 ? named(argv[1]) : NULL;
    if (!q) {
        fprintf(stderr, "quality_knobs: expected one preset or measured configuration name\n");
        return 2;
    }
    printf("steps %d\nskyview_lut %d %d\nskyview_steps %d\ntransmittance_lut %d %d\nmultiscatter_lut %d\n"
           "multiscatter_directions %d\nrender_scale %g\nbloom_res %s\n", q->steps, q->skyview_width,
           q->skyview_height, q->skyview_steps, q->transmittance_width, q->transmittance_height, q->multiscatter_size,
           q->multiscatter_sqrt_dirs * q->multiscatter_sqrt_dirs, q->render_scale, q->bloom_quarter ? "quarter" : "half");
    return 0;
}
