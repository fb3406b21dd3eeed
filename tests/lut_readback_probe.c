/* The frame around sky_renderer_read_lut() (src/sky/submit.c, which submits frame_record_lut_readback() of
 * src/sky/frame.c), for the drop and mutation tests of its barriers (lut_readback.to_copy / .to_sample / .to_host;
 * tests/barrier_drops.txt, config lut_readback): a frame that
 * computes the LUTs, the readback of the transmittance LUT, and a second frame that samples the LUT again.
 * Run by tests/barrier_drop_test.sh like vksky: `--validate` and `--trace-barriers` are the only options; the
 * environment's VKSKY_DROP_BARRIER / VKSKY_WEAKEN_BARRIER apply. Exit 1 if validation reported anything. */
#include "gpu_test.h"

int main(int argc, char **argv)
{
    bool trace = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "lut_readback_probe: unknown option '%s' (accepted: --validate, --trace-barriers)\n",
                    argv[i]);
            return 2;
        }
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "lut_readback_probe: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    gpu_context ctx;
    test_context(&ctx);
    if (trace) gpu_barrier_trace(stdout);
    test_renderer t;
    sky_view view = sky_view_default();
    view.bloom = false;
    test_renderer_create(&t, &ctx, 16, 16, false, NULL, NULL);
    test_frame a = test_renderer_frame(&t, &view);   /* the LUTs are computed here */
    VkExtent2D e = sky_renderer_lut_extent(&t.r, 0);
    float *lut = malloc(sizeof(float) * 4 * e.width * e.height);
    if (lut) test_read_lut(&t.r, 0, lut);
    /* The next frame samples the LUT again: it must be back in its sampled layout (lut_readback.to_sample). */
    test_frame b = test_renderer_frame(&t, &view);
    bool finite = lut && isfinite(lut[0]) && lut[0] > 0.0f;
    free(lut);
    test_frame_free(&a);
    test_frame_free(&b);
    gpu_barrier_trace(NULL);
    test_renderer_destroy(&t);
    gpu_context_destroy(&ctx);
    unsigned messages = gpu_validation_message_count();
    if (messages) fprintf(stderr, "lut_readback_probe: validation reported %u message(s)\n", messages);
    if (!finite) fprintf(stderr, "lut_readback_probe: the LUT read back is not a positive transmittance\n");
    return messages || !finite ? 1 : 0;
}
