/* The LUT cache's frames (sky/lut_cache.h; frame_record_lut_cache_upload / _readback in src/sky/frame.c), for the
 * drop and mutation tests of their barriers (lut_cache.*; tests/barrier_drops.txt, config lut_cache): in a cache
 * directory of its own, a renderer computes the LUTs (a miss: the readback frame stores them) and renders a second
 * frame over them; a second renderer finds them (a hit: the upload replaces the LUT passes) and renders two frames.
 * A lit ground, so all three cached LUTs take part. Run by tests/barrier_drop_test.sh like vksky: `--validate` and
 * `--trace-barriers` are the only options; VKSKY_DROP_BARRIER / VKSKY_WEAKEN_BARRIER apply. Exit 1 if validation
 * reported anything, the cache was not missed then hit, or the hit's frames differ from the miss's. */
#include "gpu/pipeline_cache.h"
#include "gpu_test.h"
#include <stdlib.h>
#include <unistd.h>

/* One renderer's two frames; returns its LUT cache state after the first. */
static int two_frames(gpu_context *ctx, const sky_view *view, test_frame out[2])
{
    test_renderer t;
    sky_lut_quality q = sky_lut_quality_default();
    q.multiscatter_sqrt_dirs = 4;   /* small and quick on lavapipe */
    test_renderer_create(&t, ctx, 16, 16, false, &q, NULL);
    sky_features f = t.r.features;
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = 0.3;
    sky_renderer_set_features(&t.r, &f);
    out[0] = test_renderer_frame(&t, view);
    int state = (int)t.r.lut_cache;
    out[1] = test_renderer_frame(&t, view);   /* the LUTs sampled again: back in their sampled layout */
    test_renderer_destroy(&t);
    return state;
}

int main(int argc, char **argv)
{
    bool trace = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "lut_cache_probe: unknown option '%s' (accepted: --validate, --trace-barriers)\n", argv[i]);
            return 2;
        }
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "lut_cache_probe: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    unsetenv("VKSKY_LUT_CACHE");   /* the suite turns the cache off; this probe is about it */
    char dir[] = "/tmp/vksky_lut_cache_probe.XXXXXX";
    if (!mkdtemp(dir)) return 1;
    gpu_context ctx;
    test_context(&ctx);
    gpu_pipeline_cache_open(&ctx, dir, "lut_cache_probe");
    if (trace) gpu_barrier_trace(stdout);
    sky_view view = sky_view_default();
    view.bloom = false;
    view.pitch_deg = -10.0;   /* some ground in view */
    test_frame miss[2], hit[2];
    int first = two_frames(&ctx, &view, miss), second = two_frames(&ctx, &view, hit);
    gpu_barrier_trace(NULL);
    size_t n = 4 * 16 * 16;
    bool same = !memcmp(miss[0].linear, hit[0].linear, n * sizeof(float)) &&
                !memcmp(miss[1].display, hit[1].display, n);
    for (int i = 0; i < 2; ++i) test_frame_free(&miss[i]), test_frame_free(&hit[i]);
    gpu_pipeline_cache_close(&ctx);
    gpu_context_destroy(&ctx);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "lut_cache_probe: could not remove %s\n", dir);
    unsigned messages = gpu_validation_message_count();
    if (messages) fprintf(stderr, "lut_cache_probe: validation reported %u message(s)\n", messages);
    bool states = first == SKY_LUT_CACHE_STORED && second == SKY_LUT_CACHE_HIT;
    if (!states) fprintf(stderr, "lut_cache_probe: expected a stored miss then a hit, got states %d, %d\n", first, second);
    if (!same) fprintf(stderr, "lut_cache_probe: the frames over the uploaded LUTs differ from the computed ones\n");
    return messages || !states || !same ? 1 : 0;
}
