/* The API's renders, checked against the command-line tool (an independent path: its own context, its own display
 * image, its own PNG writer) and against each other:
 *   compare VKSKY_BIN: a DISPLAY frame through vksky_context_create_own + vksky_camera_look equals `vksky --render`'s
 *     PNG of the same view (within 1/255); the same frame on a device the test made itself (its own instance, the
 *     last queue of its last graphics+compute family) equals it too; two renderers of different sizes in one
 *     process, each equal to the CLI's PNG of its size; 100 vksky_record calls allocate nothing through the
 *     context's VkAllocationCallbacks.
 *   quality VKSKY_BIN: a renderer given its quality knob by knob (vksky_quality_config, chained from the desc: "medium"
 *     with other steps, sky mode and pass, render scale, LUT sizes and bloom mips) equals `vksky --render` with the
 *     same flags (within 1/255); its per-pass GPU timings come back named, finite and >= 0, the sky pass among them;
 *     an unknown structure type, a repeated one, a knob out of range and a frame.next are refused.
 *   cycles N: renderer create/destroy N times on one context: the live allocations through the callbacks return
 *     to the same count, and the resident set does not grow.
 * Validation + synchronization validation on throughout; any message fails. */
#include "api_host.h"
#include "io/png_io.h"
#include "luts_host_comp.h"
#include "model/medium.h"
#include "reference/ref_atmosphere.h"
#include <math.h>
#include <stdint.h>

/* Counting VkAllocationCallbacks: live blocks and calls. Each block keeps its size and alignment in the 16 bytes
 * before it (the header is `align` bytes, align >= 16). */
typedef struct counter { long live, calls; } counter;
static void *count_alloc(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)scope;
    counter *c = user;
    if (align < 16) align = 16;
    unsigned char *base = aligned_alloc(align, ((size + 2 * align - 1) / align) * align);
    if (!base) return NULL;
    c->live++, c->calls++;
    size_t *header = (size_t *)(base + align);
    header[-1] = align, header[-2] = size;
    return base + align;
}
static void count_free(void *user, void *mem)
{
    if (!mem) return;
    counter *c = user;
    c->live--;
    free((unsigned char *)mem - ((size_t *)mem)[-1]);
}
static void *count_realloc(void *user, void *old, size_t size, size_t align, VkSystemAllocationScope scope)
{
    if (!old) return count_alloc(user, size, align, scope);
    if (!size) { count_free(user, old); return NULL; }
    void *p = count_alloc(user, size, align, scope);
    if (!p) return NULL;
    size_t old_size = ((size_t *)old)[-2];
    memcpy(p, old, old_size < size ? old_size : size);
    count_free(user, old);
    return p;
}

static VkAllocationCallbacks counting(counter *c)
{
    return (VkAllocationCallbacks){.pUserData = c, .pfnAllocation = count_alloc, .pfnReallocation = count_realloc,
                                   .pfnFree = count_free};
}

static const double YAW = 30.0, PITCH = 10.0, FOV = 75.0, EV100 = 12.0;

/* `vksky --render` of the test's view at width x height: the reference PNG's pixels (RGBA). */
static uint8_t *cli_png_with(const char *vksky, const char *dir, int width, int height, const char *scene,
                             const char *extra)
{
    char path[512], cmd[1400], err[200];
    snprintf(path, sizeof path, "%s/cli_%dx%d_%s.png", dir, width, height, scene ? scene : "earth");
    snprintf(cmd, sizeof cmd, "%s %s%s --render %s --width %d --height %d --yaw %g --pitch %g --fov %g --exposure %g "
             "--altitude 0.001 --quality medium --validate %s", vksky, scene ? "--scene " : "", scene ? scene : "", path,
             width, height, YAW, PITCH, FOV, EV100, extra);
    if (system(cmd) != 0) {
        fprintf(stderr, "FAIL: %s\n", cmd);
        exit(1);
    }
    int w = 0, h = 0;
    uint8_t *rgba = NULL;
    if (io_read_png(path, &w, &h, &rgba, err, sizeof err) != 0 || w != width || h != height) {
        fprintf(stderr, "FAIL: %s: %s\n", path, err);
        exit(1);
    }
    return rgba;
}

static uint8_t *cli_png(const char *vksky, const char *dir, int width, int height, const char *scene)
{
    return cli_png_with(vksky, dir, width, height, scene, "");
}

static vksky_renderer *make_renderer_of(vksky_context *c, uint32_t w, uint32_t h, vksky_output output, bool bloom)
{
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = output, .width = w,
                             .height = h, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "medium",
                             .bloom = bloom, .units = VKSKY_UNITS_PHOTOMETRIC};
    vksky_renderer *r = NULL;
    vksky_result res = vksky_renderer_create(c, &d, &r);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_create: %s", vksky_result_name(res));
    if (!r) exit(1);
    return r;
}

static vksky_renderer *make_renderer(vksky_context *c, uint32_t w, uint32_t h)
{
    return make_renderer_of(c, w, h, VKSKY_OUTPUT_DISPLAY, true);
}

/* One frame through the API into the host's image; the pixels stay in h->mapped. */
static void api_frame(host *h, vksky_renderer *r)
{
    vksky_camera cam = {.origin_altitude_m = 1.0};   /* the CLI's default camera: 1 m above the ground */
    vksky_camera_look(&cam, YAW, PITCH, FOV, (double)h->width / h->height, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = EV100, .color = host_image(h, VK_FORMAT_R8G8B8A8_SRGB)};
    host_begin(h);
    vksky_result res = vksky_record(r, h->cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
    host_end_and_read(h);
}

/* Largest difference of any channel (alpha aside), in 8-bit steps. */
static int max_difference(const uint8_t *a, const uint8_t *b, size_t pixels, const char *what)
{
    int worst = 0;
    size_t at = 0;
    for (size_t i = 0; i < pixels; ++i)
        for (int ch = 0; ch < 3; ++ch) {
            int d = abs((int)a[4 * i + ch] - (int)b[4 * i + ch]);
            if (d > worst) worst = d, at = i;
        }
    printf("%s: max difference %d/255 (pixel %zu)\n", what, worst, at);
    return worst;
}

static int compare(const char *vksky)
{
    char dir[] = "/tmp/vksky_api_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    const uint32_t W = 96, H = 54, W2 = 64, H2 = 64;
    uint8_t *cli = cli_png(vksky, dir, (int)W, (int)H, NULL), *cli2 = cli_png(vksky, dir, (int)W2, (int)H2, NULL);
    uint8_t *cli_mars = cli_png(vksky, dir, (int)W2, (int)H2, "mars");
    uint8_t *own_pixels = malloc(4 * W * H);
    /* The reference is a sky, not a blank: blue over the horizon, its rows not all alike. */
    int lo = 255, hi = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) lo = cli[4 * i + 2] < lo ? cli[4 * i + 2] : lo, hi = cli[4 * i + 2] > hi ? cli[4 * i + 2] : hi;
    HOST_CHECK(hi - lo > 40 && cli[2] > cli[0], "the CLI's reference is no sky (blue %d..%d, top-left %d,%d,%d)", lo, hi,
               cli[0], cli[1], cli[2]);

    /* 1. vksky's own device: the same view as the CLI's. Two renderers of different sizes, alive together. */
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .validation = true,
                                .message = api_message};
    vksky_context *own = NULL;
    vksky_result res = vksky_context_create_own(&od, &own);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_context_create_own: %s", vksky_result_name(res));
    if (!own) return 1;
    host h, h2;
    host_from_context(&h, own);
    host_from_context(&h2, own);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    host_create_target(&h2, W2, H2, VK_FORMAT_R8G8B8A8_SRGB);
    vksky_renderer *r = make_renderer(own, W, H), *r2 = make_renderer(own, W2, H2);
    api_frame(&h, r);
    api_frame(&h2, r2);
    api_frame(&h, r);   /* the second frame: the LUTs kept, every barrier from the previous frame's uses */
    memcpy(own_pixels, h.mapped, 4 * W * H);
    HOST_CHECK(max_difference(own_pixels, cli, W * H, "own device vs CLI") <= 1, "the API's frame differs from the CLI's");
    HOST_CHECK(max_difference(h2.mapped, cli2, W2 * H2, "second renderer vs CLI") <= 1,
               "the second renderer's frame differs from the CLI's");
    /* The first renderer resized to the second's size, then given Mars: each frame equals the CLI's. */
    HOST_CHECK(vksky_renderer_resize(r, W2, H2) == VKSKY_SUCCESS, "vksky_renderer_resize");
    api_frame(&h2, r);
    HOST_CHECK(max_difference(h2.mapped, cli2, W2 * H2, "resized renderer vs CLI") <= 1,
               "the resized renderer's frame differs from the CLI's");
    HOST_CHECK(max_difference(cli_mars, cli2, W2 * H2, "(CLI Mars vs CLI Earth)") > 10,
               "Mars and Earth look alike: the Mars comparison would prove nothing");
    vksky_scene *mars = NULL;
    HOST_CHECK(vksky_scene_load("mars", api_message, NULL, &mars) == VKSKY_SUCCESS, "vksky_scene_load mars");
    HOST_CHECK(mars && vksky_renderer_set_scene(r, mars) == VKSKY_SUCCESS, "vksky_renderer_set_scene");
    vksky_scene_destroy(mars);
    api_frame(&h2, r);
    HOST_CHECK(max_difference(h2.mapped, cli_mars, W2 * H2, "Mars (set_scene) vs CLI --scene mars") <= 1,
               "the Mars frame differs from the CLI's");
    vksky_renderer_destroy(r2);
    vksky_renderer_destroy(r);
    host_destroy_target(&h2);
    host_destroy_target(&h);
    HOST_CHECK(vksky_context_validation_message_count(own) == 0, "%u validation messages",
               vksky_context_validation_message_count(own));
    vksky_context_destroy(own);

    /* 2. The host's own device, with counting allocation callbacks: same image; no allocation per frame. */
    counter count = {0};
    VkAllocationCallbacks cb = counting(&count);
    host_create_device(&h, NULL);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    vksky_context_desc cd = host_context_desc(&h, &cb);
    vksky_context *hc = NULL;
    res = vksky_context_create(&cd, &hc);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_context_create: %s", vksky_result_name(res));
    if (!hc) return 1;
    r = make_renderer(hc, W, H);
    HOST_CHECK(count.calls > 0, "the renderer made nothing through the host's allocation callbacks");
    api_frame(&h, r);
    HOST_CHECK(max_difference(h.mapped, own_pixels, W * H, "host device vs own device") == 0,
               "the host device's frame differs from vksky's own device's");
    long calls_before = count.calls, live_before = count.live;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, YAW, PITCH, FOV, (double)W / H, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = EV100, .color = host_image(&h, VK_FORMAT_R8G8B8A8_SRGB)};
    for (int i = 0; i < 100; ++i) {
        host_begin(&h);
        vksky_record(r, h.cmd, &f);
        HOST_VK(vkEndCommandBuffer(h.cmd));
    }
    printf("100 vksky_record calls: %ld allocations through the callbacks (live %ld -> %ld)\n",
           count.calls - calls_before, live_before, count.live);
    HOST_CHECK(count.calls == calls_before && count.live == live_before, "vksky_record allocated");
    vksky_renderer_destroy(r);
    vksky_context_destroy(hc);
    HOST_CHECK(count.live == 0, "%ld blocks still allocated after every vksky object was destroyed", count.live);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages on the host's device", host_validation_messages);
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] + api_messages[VKSKY_SEVERITY_VALIDATION] == 0,
               "vksky reported errors");
    free(cli), free(cli2), free(cli_mars), free(own_pixels);
    char rm[600];
    snprintf(rm, sizeof rm, "rm -rf %s", dir);
    if (system(rm) != 0) return 1;
    return host_failures ? 1 : 0;
}

static long rss_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "VmRSS:", 6)) kb = atol(line + 6);
    if (f) fclose(f);
    return kb;
}

static int cycles(int n)
{
    counter count = {0};
    VkAllocationCallbacks cb = counting(&count);
    host h;
    host_create_device(&h, NULL);
    vksky_context_desc cd = host_context_desc(&h, &cb);
    /* The host's pipeline cache: the pipelines of every renderer after the first come from it (lavapipe compiles
     * at creation), as they would in an engine that keeps one. */
    VkPipelineCacheCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    HOST_VK(vkCreatePipelineCache(h.device, &pci, NULL, &cd.pipeline_cache));
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;
    /* The drivers' own caches fill over the first renderers (the NVIDIA driver's resident set climbs ~10 MB over the
     * first few hundred, then stays put over thousands): the live count must be flat after a warm-up of 10, the
     * resident set over the second half of the run. */
    long live0 = 0, rss0 = 0, rss_half = 0;
    for (int i = 0; i < n; ++i) {
        vksky_renderer *r = make_renderer_of(c, 32, 18, getenv("API_LUTS") ? VKSKY_OUTPUT_LUTS_ONLY : VKSKY_OUTPUT_DISPLAY,
                                             !getenv("API_NOBLOOM"));
        vksky_renderer_destroy(r);
        if (i == 9) live0 = count.live, rss0 = rss_kb();
        if (i == n / 2) rss_half = rss_kb();
    }
    long rss1 = rss_kb();
    printf("%d renderers: live blocks %ld -> %ld, VmRSS %ld -> %ld (half-way) -> %ld kB\n", n, live0, count.live, rss0,
           rss_half, rss1);
    HOST_CHECK(count.live == live0, "live allocations grew from %ld to %ld", live0, count.live);
    HOST_CHECK(rss1 - rss_half < 4 * 1024, "resident set grew by %ld kB over the second half", rss1 - rss_half);
    vksky_context_destroy(c);
    vkDestroyPipelineCache(h.device, cd.pipeline_cache, NULL);
    host_destroy_device(&h, NULL);
    HOST_CHECK(count.live == 0, "%ld blocks left after the context", count.live);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    return host_failures ? 1 : 0;
}

/* VKSKY_OUTPUT_LUTS_ONLY on the host's device: the host's compute shader (include/vksky_luts.glsl) samples the
 * transmittance LUT as the CPU reference integrates it (within 1 %: a bilinear tap of a half-float LUT), and reads a
 * multi-scattering LUT's Psi as the model's quadrature gives it with the same directions (within 2 %), and a
 * sky-view radiance that is finite, positive and at the zenith bluer than red. */
static int luts(void)
{
    host h;
    host_create_device(&h, NULL);
    host_create_target(&h, 4, 4, VK_FORMAT_R8G8B8A8_SRGB);   /* its command buffer and fence */
    vksky_context_desc cd = host_context_desc(&h, NULL);
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;
    vksky_renderer *r = make_renderer_of(c, 0, 0, VKSKY_OUTPUT_LUTS_ONLY, false);
    vksky_luts l;
    HOST_CHECK(vksky_get_luts(r, &l) == VKSKY_SUCCESS && l.transmittance && l.multiscatter && l.skyview && l.sampler,
               "vksky_get_luts");
    host_luts pass;
    host_luts_create(&h, &pass, &l, spv_luts_host, sizeof spv_luts_host, 64);
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 1.0, 0.1);
    vksky_frame f = {.camera = &cam};
    host_begin(&h);
    for (int frame = 0; frame < 2; ++frame) {   /* twice: the second frame's LUT writes after the first's reads */
        if (frame > 0) host_buffer_waw(&h, pass.buffer);
        HOST_CHECK(vksky_record(r, h.cmd, &f) == VKSKY_SUCCESS, "vksky_record LUTS_ONLY");
        host_luts_record(&h, &pass);
        f.force_luts = true;
    }
    host_submit(&h, pass.buffer);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    double worst = 0.0, worst_ms = 0.0;
    for (uint32_t i = 0; i < pass.width; ++i) {
        double mu = 0.05 + (1.0 - 0.05) * i / (pass.width - 1), t[3], psi[3];
        ref_transmittance(&earth, 1.0, mu, 2000, t);
        for (int ch = 0; ch < 3; ++ch) {
            double e = fabs(pass.texels[4 * i + ch] - t[ch]) / t[ch];
            worst = e > worst ? e : worst;
        }
        /* Psi by the model's own quadrature with the preset's directions (medium: 32x32) and steps, a few texels. */
        if (i % 16 == 0) {
            ref_multiscatter(&earth, 1.0, mu, 32, 20, 40, psi);
            for (int ch = 0; ch < 3; ++ch) {
                double e = fabs(pass.texels[4 * (pass.width + i) + ch] - psi[ch]) / psi[ch];
                worst_ms = e > worst_ms ? e : worst_ms;
            }
        }
        const float *ms = pass.texels + 4 * (pass.width + i), *sky = pass.texels + 4 * (2 * pass.width + i);
        for (int ch = 0; ch < 3; ++ch)
            HOST_CHECK(isfinite(ms[ch]) && ms[ch] > 0 && isfinite(sky[ch]) && sky[ch] > 0,
                       "texel %u: multiscatter %g, sky-view %g", i, ms[ch], sky[ch]);
    }
    const float *zenith = pass.texels + 4 * (3 * pass.width - 1);
    printf("LUTS_ONLY: the host's transmittance within %.3f %% of the CPU reference, Psi within %.2f %%; zenith sky-view "
           "%g %g %g\n", 100 * worst, 100 * worst_ms, zenith[0], zenith[1], zenith[2]);
    HOST_CHECK(worst < 0.01, "transmittance off the reference by %.3f %%", 100 * worst);
    HOST_CHECK(worst_ms < 0.02, "Psi off the reference by %.2f %% (the LUT stores Psi^(1/4) in half floats)", 100 * worst_ms);
    HOST_CHECK(zenith[2] > zenith[0], "the zenith is not bluer than red");
    host_luts_destroy(&h, &pass);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    return host_failures ? 1 : 0;
}

static int quality(const char *vksky)
{
    char dir[] = "/tmp/vksky_api_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    const uint32_t W = 80, H = 48;
    uint8_t *cli = cli_png_with(vksky, dir, (int)W, (int)H, NULL,
                                "--steps 20 --sky-mode march --sky-pass compute --render-scale 0.5 "
                                "--transmittance-steps 30 --multiscatter-lut 16 --skyview-steps 24 --bloom-mips 3");
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .validation = true,
                                .message = api_message};
    vksky_context *c = NULL;
    if (vksky_context_create_own(&od, &c) != VKSKY_SUCCESS) return 1;
    vksky_quality_config q;
    HOST_CHECK(vksky_quality_config_preset("medium", &q) == VKSKY_SUCCESS, "preset medium");
    HOST_CHECK(vksky_quality_config_preset("auto", &q) == VKSKY_ERROR_INVALID_ARGUMENT, "auto is not a fixed config");
    vksky_quality_config_preset("medium", &q);
    q.view_steps = 20, q.sky_mode = VKSKY_SKY_MODE_MARCH, q.sky_pass = VKSKY_SKY_PASS_COMPUTE, q.render_scale = 0.5;
    q.transmittance_steps = 30, q.multiscatter_size = 16, q.skyview_steps = 24, q.bloom_mips = 3;
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .next = &q, .output = VKSKY_OUTPUT_DISPLAY,
                             .width = W, .height = H, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "ultra",
                             .bloom = true, .units = VKSKY_UNITS_PHOTOMETRIC};   /* .quality: overridden by q */
    vksky_renderer *r = NULL;
    HOST_CHECK(vksky_renderer_create(c, &d, &r) == VKSKY_SUCCESS, "vksky_renderer_create with a quality config");
    if (!r) return 1;
    host h;
    host_from_context(&h, c);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    api_frame(&h, r);
    HOST_CHECK(max_difference(h.mapped, cli, W * H, "explicit quality vs CLI flags") <= 1,
               "the explicit quality's frame differs from the CLI's with the same flags");

    /* Timings of that frame (the host waited for it in api_frame). */
    vksky_pass_timing t[64];
    uint32_t n = 0, n2 = 0;
    vksky_result tr = vksky_renderer_get_timings(r, t, 64, &n);
    if (tr == VKSKY_ERROR_UNSUPPORTED) printf("timings: the device has no timestamps\n");
    else {
        HOST_CHECK(tr == VKSKY_SUCCESS && n > 0 && n <= 64, "vksky_renderer_get_timings: %s, %u passes",
                   vksky_result_name(tr), n);
        bool sky = false;
        for (uint32_t i = 0; i < n && i < 64; ++i) {
            HOST_CHECK(t[i].name && isfinite(t[i].gpu_ms) && t[i].gpu_ms >= 0.0, "pass %u: %s %g", i,
                       t[i].name ? t[i].name : "(null)", t[i].gpu_ms);
            sky |= t[i].name && strstr(t[i].name, "sky") != NULL;
            printf("timing %s %.4f ms\n", t[i].name, t[i].gpu_ms);
        }
        HOST_CHECK(sky, "no sky pass among the %u timed passes", n);
        HOST_CHECK(vksky_renderer_get_timings(r, t, 1, &n2) == VKSKY_SUCCESS && n2 == n, "capacity 1: count %u", n2);
    }
    HOST_CHECK(vksky_renderer_get_timings(r, NULL, 4, &n2) == VKSKY_ERROR_INVALID_ARGUMENT, "NULL out, capacity 4");

    /* Refusals: one message each, no renderer. */
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    vksky_renderer *bad = NULL;
    vksky_chain unknown = {(vksky_structure_type)99, NULL};
    d.next = &unknown;
    HOST_CHECK(vksky_renderer_create(c, &d, &bad) == VKSKY_ERROR_INVALID_ARGUMENT && !bad, "an unknown type");
    vksky_quality_config q2 = q;
    q2.next = &q;
    d.next = &q2;
    HOST_CHECK(vksky_renderer_create(c, &d, &bad) == VKSKY_ERROR_INVALID_ARGUMENT && !bad, "a type twice");
    q2 = q, q2.render_scale = 0.05;
    HOST_CHECK(vksky_renderer_create(c, &d, &bad) == VKSKY_ERROR_INVALID_ARGUMENT && !bad, "render_scale 0.05");
    q2 = q, q2.view_max_steps = q.view_steps - 1;
    HOST_CHECK(vksky_renderer_create(c, &d, &bad) == VKSKY_ERROR_INVALID_ARGUMENT && !bad, "max steps < steps");
    q2 = q, q2.sky_mode = (vksky_sky_mode)7;
    HOST_CHECK(vksky_renderer_create(c, &d, &bad) == VKSKY_ERROR_INVALID_ARGUMENT && !bad, "sky_mode 7");
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, YAW, PITCH, FOV, (double)W / H, 0.1);
    vksky_frame f = {.next = &unknown, .camera = &cam, .exposure = EV100, .color = host_image(&h, VK_FORMAT_R8G8B8A8_SRGB)};
    host_begin(&h);
    HOST_CHECK(vksky_record(r, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a frame.next");
    vkEndCommandBuffer(h.cmd);
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 6, "%u error messages for 6 refusals",
               api_messages[VKSKY_SEVERITY_ERROR] - errors);

    vksky_renderer_destroy(r);
    host_destroy_target(&h);
    HOST_CHECK(vksky_context_validation_message_count(c) == 0, "%u validation messages",
               vksky_context_validation_message_count(c));
    vksky_context_destroy(c);
    free(cli);
    char rm[600];
    snprintf(rm, sizeof rm, "rm -rf %s", dir);
    if (system(rm) != 0) fprintf(stderr, "api_render: could not remove %s\n", dir);
    return host_failures ? 1 : 0;
}

/* The command-line tool's own path through the API (issue 25 item 1; app/runs/headless_api.c): a scene made of a
 * command line (vksky_scene_from_args, quality "scene"), the view as given (vksky_frame_view) and the renderer's own
 * images read back (vksky_readback_config). Against the same frame with rays from camera matrices (vksky_camera_look,
 * an independent construction: within 1/255 as `compare` allows) and the host's own image; the refusals (and those of
 * vksky_context_set_device_features, which the CLI calls on the device it adopts). */
static int cli_view(void)
{
    const uint32_t W = 48, H = 27;
    vksky_context *c = host_own_context();
    host h;
    host_from_context(&h, c);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    char *argv[] = {"vksky", "--width", "48", "--height", "27", "--yaw", "30", "--pitch", "10", "--fov", "75",
                    "--exposure", "12", "--altitude", "0.001", "--quality", "medium"};
    vksky_scene *scene = host_scene_of_args((int)(sizeof argv / sizeof *argv), argv);
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc d = host_readback_desc(&rb, scene, W, H, true);
    vksky_renderer *own = host_renderer(c, &d);
    vksky_result res;
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = YAW, .pitch_deg = PITCH,
                             .fov_deg = FOV};
    vksky_frame f = {.next = &view, .exposure = EV100};
    host_begin(&h);
    res = vksky_record(own, h.cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record (frame view): %s", vksky_result_name(res));
    HOST_VK(vkEndCommandBuffer(h.cmd));
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = h.cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci};
    HOST_VK(vkQueueSubmit2(h.queue, 1, &si, h.fence));
    HOST_VK(vkWaitForFences(h.device, 1, &h.fence, VK_TRUE, UINT64_MAX));
    HOST_VK(vkResetFences(h.device, 1, &h.fence));
    vksky_readback px;
    res = vksky_renderer_get_readback(own, &px);
    HOST_CHECK(res == VKSKY_SUCCESS && px.width == W && px.height == H && px.display_rgba8 && px.linear_rgba16f,
               "vksky_renderer_get_readback: %s", vksky_result_name(res));
    if (res != VKSKY_SUCCESS) return 1;
    uint8_t *display = malloc(4 * (size_t)W * H);
    memcpy(display, px.display_rgba8, 4 * (size_t)W * H);
    /* The scene-linear AOV: finite, non-negative halfs (exponent not all ones, sign clear); a daylight sky at the top
     * (Rayleigh: blue over red, both lit; positive halfs order as their bits). */
    int bad = 0;
    for (size_t i = 0; i < 4 * (size_t)W * H; ++i) bad += (px.linear_rgba16f[i] & 0x7c00) == 0x7c00 || (px.linear_rgba16f[i] & 0x8000);
    HOST_CHECK(bad == 0, "%d linear halfs not finite or negative", bad);
    HOST_CHECK(px.linear_rgba16f[2] > px.linear_rgba16f[0] && px.linear_rgba16f[0] > 0, "top-left %#x, %#x, %#x: no "
               "daylight sky in the linear AOV", px.linear_rgba16f[0], px.linear_rgba16f[1], px.linear_rgba16f[2]);

    /* The same frame from camera matrices into the host's image. */
    vksky_renderer *matrices = make_renderer(c, W, H);
    api_frame(&h, matrices);
    HOST_CHECK(max_difference(display, h.mapped, (size_t)W * H, "frame view vs camera matrices") <= 1,
               "the view as given differs from the camera matrices' by more than 1/255");

    /* Refusals, one message each. */
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    vksky_scene *bad_scene = NULL;
    char *bad_argv[] = {"vksky", "--fov", "400"};
    HOST_CHECK(vksky_scene_from_args(3, bad_argv, api_message, NULL, &bad_scene) == VKSKY_ERROR_INVALID_ARGUMENT &&
               !bad_scene, "--fov 400 accepted");
    vksky_renderer *none = NULL;
    d.scene = NULL;   /* Earth, not a command line: no quality of its own */
    HOST_CHECK(vksky_renderer_create(c, &d, &none) == VKSKY_ERROR_INVALID_ARGUMENT && !none, "quality scene of Earth");
    d.scene = scene, d.target_format = VK_FORMAT_R8G8B8A8_UNORM;
    HOST_CHECK(vksky_renderer_create(c, &d, &none) == VKSKY_ERROR_INVALID_ARGUMENT && !none, "readback into UNORM");
    view.fov_deg = 175.0;
    host_begin(&h);
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "frame view fov 175");
    HOST_CHECK(vksky_renderer_get_readback(matrices, &px) == VKSKY_ERROR_INVALID_ARGUMENT, "readback of a host image");
    view.fov_deg = FOV;
    vksky_auto_exposure metered = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, .slot = VKSKY_AUTO_EXPOSURE_SLOTS};
    view.next = &metered;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "auto exposure slot past the last");
    metered.slot = 0, metered.next = &view;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a chain that loops");
    view.next = NULL;
    /* vksky_frame_band (issue 25): twice, out of range, a perspective band without a view, chained from a desc. */
    vksky_frame_band band = {.type = VKSKY_STRUCTURE_TYPE_FRAME_BAND, .projection = VKSKY_PROJECTION_TYPE_EQUIRECT,
                             .whole_width = W, .whole_height = W / 2};
    vksky_frame_band band2 = band;
    band.next = &band2;
    f.next = &band;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a band twice");
    band.next = NULL, band.whole_width = W + 1;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a band wider than the renderer");
    band.whole_width = W, band.meter_first_row = 1, band.meter_rows = H;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "meter rows past the frame's");
    band.meter_first_row = band.meter_rows = 0, band.projection = VKSKY_PROJECTION_TYPE_PERSPECTIVE;
    HOST_CHECK(vksky_record(own, h.cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a perspective band without a view");
    f.next = &view;
    vksky_exposure ev;
    HOST_CHECK(vksky_renderer_get_exposure(own, VKSKY_AUTO_EXPOSURE_SLOTS, &ev) == VKSKY_ERROR_INVALID_ARGUMENT,
               "exposure slot past the last");
    vkEndCommandBuffer(h.cmd);
    vksky_device_requirements enabled;
    vksky_get_device_requirements(&enabled);
    HOST_CHECK(vksky_context_set_device_features(c, &enabled) == VKSKY_ERROR_INVALID_ARGUMENT,
               "device features set after a renderer");
    enabled.maintenance4 = false;
    HOST_CHECK(vksky_context_set_device_features(c, &enabled) == VKSKY_ERROR_UNSUPPORTED, "maintenance4 off");
    d.target_format = VK_FORMAT_R8G8B8A8_SRGB, rb.next = &band;   /* a frame's struct in a renderer's chain */
    HOST_CHECK(vksky_renderer_create(c, &d, &none) == VKSKY_ERROR_INVALID_ARGUMENT && !none, "a band in a desc");
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 13, "%u error messages for 13 refusals with messages",
               api_messages[VKSKY_SEVERITY_ERROR] - errors);

    vksky_renderer_destroy(own);
    vksky_renderer_destroy(matrices);
    vksky_scene_destroy(scene);
    host_destroy_target(&h);
    HOST_CHECK(vksky_context_validation_message_count(c) == 0, "%u validation messages",
               vksky_context_validation_message_count(c));
    vksky_context_destroy(c);
    free(display);
    return host_failures ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "cli_view")) return cli_view();
    if (argc == 3 && !strcmp(argv[1], "quality")) return quality(argv[2]);
    if (argc == 2 && !strcmp(argv[1], "luts")) return luts();
    if (argc == 3 && !strcmp(argv[1], "compare")) return compare(argv[2]);
    if (argc == 3 && !strcmp(argv[1], "cycles")) return cycles(atoi(argv[2]));
    fprintf(stderr, "usage: api_render compare VKSKY_BIN | quality VKSKY_BIN | cycles N | luts | cli_view\n");
    return 2;
}
