/* Shared helpers of the GPU tests: a validated context (validation + synchronization validation, always on),
 * rendering a view into host memory, and check macros. Any validation message fails the test. */
#ifndef VKSKY_GPU_TEST_H
#define VKSKY_GPU_TEST_H
#include "io/half_float.h"
#include "reference/ref_atmosphere.h"
#include "gpu/pipeline_cache.h"
#include "sky/submit.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"

static const double TEST_DEG = 3.14159265358979323846 / 180.0;
static const double SUN_RADIUS_RAD = 0.5 * 0.53 * 3.14159265358979323846 / 180.0;

static inline void test_context(gpu_context *ctx)
{
    gpu_context_desc desc = {.validation = true, .device_index = -1};
    if (gpu_context_create(ctx, &desc) != 0) {
        fprintf(stderr, "FAIL: no Vulkan device with the validation layer\n");
        exit(1);
    }
    /* The suite's shared LUT cache (tests/CMakeLists.txt, VKSKY_SHARED_LUT_TESTS: VKSKY_LUT_CACHE=1): the directory
     * vksky's own processes use, $XDG_CACHE_HOME/vksky, so that a medium's LUTs at one LUT setting (--quality
     * ultra's for the Earth: ~25 s on lavapipe) are computed once per suite run, by whichever test meets them first,
     * and uploaded byte for byte by the others (ctest lut_cache). Anything else (the binary run by hand): none. */
    const char *share = getenv("VKSKY_LUT_CACHE"), *xdg = getenv("XDG_CACHE_HOME");
    if (share && !strcmp(share, "1") && xdg && xdg[0] == '/') {
        char dir[1024];
        if (snprintf(dir, sizeof dir, "%s/vksky", xdg) < (int)sizeof dir) gpu_cache_dir_attach(ctx, dir);
    }
}

/* A rendered frame on the host: scene-linear RGBA floats (HDR + bloom if on) and the 8-bit display image. */
typedef struct test_frame {
    int width, height;
    float *linear;
    unsigned char *display;
} test_frame;

/* A renderer kept across frames (its LUTs are computed once: only the view changes between frames).
 * `lut` NULL: the default LUT quality; `atmosphere` NULL: Earth (model_atmosphere_earth). */
typedef struct test_renderer {
    sky_renderer r;
    int width, height;
} test_renderer;

static inline void test_renderer_create(test_renderer *t, gpu_context *ctx, int width, int height, bool bloom,
                                        const sky_lut_quality *lut, const model_atmosphere *atmosphere)
{
    sky_renderer_desc desc = {.width = (uint32_t)width, .height = (uint32_t)height, .bloom = bloom,
                              .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    desc.lut = lut ? *lut : sky_lut_quality_default();
    t->width = width, t->height = height;
    sky_renderer_create(&t->r, ctx, &desc);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    sky_renderer_set_atmosphere(&t->r, atmosphere ? atmosphere : &a, SUN_RADIUS_RAD);
}

static inline test_frame test_renderer_frame(test_renderer *t, const sky_view *view)
{
    frame_desc f = {.view = view};
    sky_renderer_render(&t->r, &f);
    size_t n = (size_t)t->width * t->height;
    test_frame out = {t->width, t->height, malloc(sizeof(float) * 4 * n), malloc(4 * n)};
    const uint16_t *half = t->r.readback_linear.mapped;
    for (size_t i = 0; i < 4 * n; ++i) out.linear[i] = io_half_to_float(half[i]);
    memcpy(out.display, t->r.readback_display.mapped, 4 * n);
    return out;
}

/* A LUT on the host as RGBA floats (rgba_out holds 4 x the extent's texels; untouched when the variant has no such
   LUT): the renderer hands back the stored texels, half floats are widened here. */
static inline void test_read_lut(sky_renderer *r, int which, float *rgba_out)
{
    VkExtent2D e = sky_renderer_lut_extent(r, which);
    size_t count = (size_t)e.width * e.height * 4;
    void *texels = malloc(count * sizeof(float));
    if (!texels) return;
    VkFormat format = sky_renderer_read_lut(r, which, texels);
    if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        memcpy(rgba_out, texels, count * sizeof(float));
    } else if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        const uint16_t *h = texels;
        for (size_t i = 0; i < count; ++i) rgba_out[i] = io_half_to_float(h[i]);
    }
    free(texels);
}

static inline void test_renderer_destroy(test_renderer *t) { sky_renderer_destroy(&t->r); }

/* One frame from a fresh renderer. */
static inline test_frame test_render_atmosphere(gpu_context *ctx, const sky_view *view, int width, int height,
                                                const sky_lut_quality *lut, const model_atmosphere *atmosphere)
{
    test_renderer t;
    test_renderer_create(&t, ctx, width, height, view->bloom, lut, atmosphere);
    test_frame out = test_renderer_frame(&t, view);
    test_renderer_destroy(&t);
    return out;
}

static inline test_frame test_render_quality(gpu_context *ctx, const sky_view *view, int width, int height,
                                             const sky_lut_quality *lut)
{
    return test_render_atmosphere(ctx, view, width, height, lut, NULL);
}

static inline test_frame test_render(gpu_context *ctx, const sky_view *view, int width, int height)
{
    return test_render_quality(ctx, view, width, height, NULL);
}

static inline void test_frame_free(test_frame *f)
{
    free(f->linear);
    free(f->display);
}

static inline const float *test_pixel(const test_frame *f, int x, int y) { return f->linear + 4 * ((size_t)y * f->width + x); }

static inline double luminance(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

/* Every pixel finite and non-negative. Returns the number of bad pixels. */
static inline int count_bad_pixels(const test_frame *f)
{
    int bad = 0;
    for (size_t i = 0; i < 4 * (size_t)f->width * f->height; ++i)
        if (!isfinite(f->linear[i]) || f->linear[i] < 0.0f) ++bad;
    return bad;
}

static inline int test_finish(const char *name)
{
    unsigned messages = gpu_validation_message_count();
    CHECK(messages == 0, "validation reported %u messages", messages);
    if (check_failures) fprintf(stderr, "%s: %d failure(s)\n", name, check_failures);
    else printf("%s: ok\n", name);
    return check_failures ? 1 : 0;
}
#endif
