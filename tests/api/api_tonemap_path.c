/* The tone map's two paths into the host's image (include/vksky.h, "The tone map's path"), against the command line:
 *   - without bloom (the tone map alone differs): the fragment path into an R8G8B8A8_SRGB image (no
 *     vksky_display_config: as before) and the compute path into an R8G8B8A8_UNORM image of usage STORAGE
 *     (vksky_display_config COMPUTE: the sRGB curve in the shader) agree within 1/255 everywhere, and each equals
 *     `vksky --render --no-bloom`'s PNG of the same view within 1/255 (as tests/api/api_render.c's compare defines it);
 *   - with bloom: the compute path equals `vksky --render --post-pass compute` (the command line's own display image,
 *     the same compute chain and tone map) within 1/255, the fragment path `vksky --render` (lavapipe: the fragment
 *     chain) within 1/255, and the two paths each other within the bounds of ctest post_compare (2 levels, 0.25 on
 *     average: the compute chain's own bilinear weights and its last upsample fused into the tone map,
 *     tests/post_compare_test.sh says why); FRAGMENT into the storage image equals the fragment path within 1/255;
 *   - a second storage image (a second view: a second descriptor set) gets the same bytes as the first; the second
 *     frame of each renderer (barriers from the previous frame's copy) the first's;
 *   - the traces: the compute path's frames name host.color.to_compute_tonemap and host.color.compute_to_after and
 *     no host.color.to_attachment, the fragment path's the opposite;
 *   - AUTO: compute on a GPU, fragment on a CPU implementation (lavapipe), fragment without STORAGE usage;
 *   - refusals: COMPUTE for an sRGB format or without STORAGE usage (UNSUPPORTED), a path out of range or beside a
 *     readback config (INVALID_ARGUMENT), each with one message.
 * Validation + synchronization validation on throughout; any message fails. */
#include "api_host.h"
#include "io/png_io.h"

static const double YAW = 30.0, PITCH = 10.0, FOV = 75.0, EV100 = 12.0;
enum { W = 96, H = 54 };

static struct { char lines[4096][160]; int count; } trace;
static void on_trace(void *user, const char *line)
{
    (void)user;
    if (trace.count < 4096) snprintf(trace.lines[trace.count++], sizeof trace.lines[0], "%s", line);
}
static int traced(const char *name)
{
    int n = 0;
    for (int i = 0; i < trace.count; ++i) n += strstr(trace.lines[i], name) != NULL;
    return n;
}

/* `vksky --render` of the test's view (api_render.c's reference) with `extra` flags: the PNG's pixels (RGBA). */
static uint8_t *cli_png(const char *vksky, const char *dir, const char *name, const char *extra)
{
    char path[512], cmd[1400], err[200];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    snprintf(cmd, sizeof cmd, "%s --render %s --width %d --height %d --yaw %g --pitch %g --fov %g --exposure %g "
             "--altitude 0.001 --quality medium --validate %s", vksky, path, W, H, YAW, PITCH, FOV, EV100, extra);
    if (system(cmd) != 0) {
        fprintf(stderr, "FAIL: %s\n", cmd);
        exit(1);
    }
    int w = 0, h = 0;
    uint8_t *rgba = NULL;
    if (io_read_png(path, &w, &h, &rgba, err, sizeof err) != 0 || w != W || h != H) {
        fprintf(stderr, "FAIL: %s: %s\n", path, err);
        exit(1);
    }
    return rgba;
}

/* Mean difference over the channels (alpha aside), in 8-bit steps. */
static double mean_difference(const uint8_t *a, const uint8_t *b)
{
    double sum = 0.0;
    for (size_t i = 0; i < (size_t)W * H; ++i)
        for (int ch = 0; ch < 3; ++ch) sum += abs((int)a[4 * i + ch] - (int)b[4 * i + ch]);
    return sum / (3.0 * W * H);
}

/* Largest difference of any channel (alpha aside), in 8-bit steps. */
static int max_difference(const uint8_t *a, const uint8_t *b, const char *what)
{
    int worst = 0;
    size_t at = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i)
        for (int ch = 0; ch < 3; ++ch) {
            int d = abs((int)a[4 * i + ch] - (int)b[4 * i + ch]);
            if (d > worst) worst = d, at = i;
        }
    printf("%s: max difference %d/255 (pixel %zu)\n", what, worst, at);
    return worst;
}

static vksky_result make_bloom(vksky_context *c, VkFormat format, const vksky_display_config *dc, const void *more,
                               bool bloom, vksky_renderer **r)
{
    vksky_display_config chained;
    if (dc) chained = *dc, chained.next = more;
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .next = dc ? (const void *)&chained : more,
                             .output = VKSKY_OUTPUT_DISPLAY, .width = W, .height = H, .target_format = format,
                             .quality = "medium", .bloom = bloom, .units = VKSKY_UNITS_PHOTOMETRIC};
    return vksky_renderer_create(c, &d, r);
}
static vksky_result make(vksky_context *c, VkFormat format, const vksky_display_config *dc, const void *more,
                         vksky_renderer **r)
{
    return make_bloom(c, format, dc, more, true, r);
}

/* Two frames into the host's image, each copied out; the last one's pixels (the first's checked equal). */
static void frames(host *h, vksky_renderer *r, VkFormat format, uint8_t *out)
{
    vksky_camera cam = {.origin_altitude_m = 1.0};   /* the CLI's default camera: 1 m above the ground */
    vksky_camera_look(&cam, YAW, PITCH, FOV, (double)W / H, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = EV100, .color = host_image(h, format)};
    for (int k = 0; k < 2; ++k) {
        host_begin(h);
        vksky_result res = vksky_record(r, h->cmd, &f);
        HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
        host_end_and_read(h);
        if (k == 1) HOST_CHECK(max_difference(out, h->mapped, "second frame vs first") == 0, "the frames differ");
        memcpy(out, h->mapped, 4 * (size_t)W * H);
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: api_tonemap_path VKSKY_BIN\n");
        return 2;
    }
    char dir[] = "/tmp/vksky_tonemap_path_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    uint8_t *cli = cli_png(argv[1], dir, "cli", ""), *cli_compute = cli_png(argv[1], dir, "compute", "--post-pass compute");
    uint8_t *cli_nobloom = cli_png(argv[1], dir, "nobloom", "--no-bloom");
    vksky_context *c = host_own_context();
    vksky_context_set_trace(c, VKSKY_TRACE_BARRIERS, on_trace, NULL);
    const VkImageUsageFlags STORAGE = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                      VK_IMAGE_USAGE_STORAGE_BIT;
    host srgb, unorm, unorm2;
    host_from_context(&srgb, c), host_from_context(&unorm, c), host_from_context(&unorm2, c);
    host_create_target(&srgb, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    host_create_target_usage(&unorm, W, H, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
    host_create_target_usage(&unorm2, W, H, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
    static uint8_t fragment[4 * W * H], compute[4 * W * H], compute2[4 * W * H], fragment_unorm[4 * W * H];
    static uint8_t fragment0[4 * W * H], compute0[4 * W * H];
    vksky_display_config compute_cfg = {.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG, .target_usage = STORAGE,
                                        .tonemap_path = VKSKY_TONEMAP_PATH_COMPUTE};

    /* 1. Without bloom: the tone map alone. The fragment path (no config) into the sRGB image, the compute path into
     * the storage image. */
    vksky_renderer *rf = NULL, *rc = NULL, *ra = NULL, *rn = NULL, *rx = NULL, *rf0 = NULL, *rc0 = NULL;
    HOST_CHECK(make_bloom(c, VK_FORMAT_R8G8B8A8_SRGB, NULL, NULL, false, &rf0) == VKSKY_SUCCESS, "fragment, no bloom");
    HOST_CHECK(make_bloom(c, VK_FORMAT_R8G8B8A8_UNORM, &compute_cfg, NULL, false, &rc0) == VKSKY_SUCCESS,
               "compute, no bloom");
    if (!rf0 || !rc0) return 1;
    HOST_CHECK(vksky_renderer_get_tonemap_path(rf0) == VKSKY_TONEMAP_PATH_FRAGMENT, "no config: not fragment");
    HOST_CHECK(vksky_renderer_get_tonemap_path(rc0) == VKSKY_TONEMAP_PATH_COMPUTE, "COMPUTE asked: not compute");
    trace.count = 0;
    frames(&srgb, rf0, VK_FORMAT_R8G8B8A8_SRGB, fragment0);
    HOST_CHECK(traced("host.color.to_attachment") == 2 && traced("host.color.to_compute_tonemap") == 0,
               "the fragment frames' trace: to_attachment %d, to_compute_tonemap %d", traced("host.color.to_attachment"),
               traced("host.color.to_compute_tonemap"));
    trace.count = 0;
    frames(&unorm, rc0, VK_FORMAT_R8G8B8A8_UNORM, compute0);
    HOST_CHECK(traced("host.color.to_compute_tonemap") == 2 && traced("host.color.compute_to_after") == 2 &&
               traced("host.color.to_attachment") == 0 && traced("host.color.to_after") == 0,
               "the compute frames' trace: to_compute_tonemap %d, compute_to_after %d, to_attachment %d",
               traced("host.color.to_compute_tonemap"), traced("host.color.compute_to_after"),
               traced("host.color.to_attachment"));
    HOST_CHECK(max_difference(compute0, fragment0, "no bloom: compute path vs fragment path") <= 1,
               "the two tone maps differ");
    HOST_CHECK(max_difference(fragment0, cli_nobloom, "no bloom: fragment path vs CLI --no-bloom") <= 1,
               "the fragment path differs from the CLI");
    HOST_CHECK(max_difference(compute0, cli_nobloom, "no bloom: compute path vs CLI --no-bloom") <= 1,
               "the compute path differs from the CLI");

    /* 2. With bloom: each path against the command line's frame of its own chain; a second storage image. */
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_SRGB, NULL, NULL, &rf) == VKSKY_SUCCESS, "the fragment renderer");
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &compute_cfg, NULL, &rc) == VKSKY_SUCCESS, "the compute renderer");
    if (!rf || !rc) return 1;
    frames(&srgb, rf, VK_FORMAT_R8G8B8A8_SRGB, fragment);
    frames(&unorm, rc, VK_FORMAT_R8G8B8A8_UNORM, compute);
    frames(&unorm2, rc, VK_FORMAT_R8G8B8A8_UNORM, compute2);
    HOST_CHECK(max_difference(compute2, compute, "second storage image vs first") == 0, "the second view differs");
    frames(&unorm, rc, VK_FORMAT_R8G8B8A8_UNORM, compute);   /* back to the first view: its set kept */
    HOST_CHECK(max_difference(compute2, compute, "first storage image again") == 0, "the first view differs");
    HOST_CHECK(max_difference(fragment, cli, "fragment path vs CLI") <= 1, "the fragment path differs");
    HOST_CHECK(max_difference(compute, cli_compute, "compute path vs CLI --post-pass compute") <= 1,
               "the compute path differs");
    int levels = max_difference(compute, fragment, "compute path vs fragment path (chains differ)");
    double mean = mean_difference(compute, fragment);
    printf("compute path vs fragment path: mean difference %.3f/255\n", mean);
    HOST_CHECK(levels <= 2 && mean <= 0.25, "the paths differ beyond post_compare's bounds (%d levels, mean %.3f)",
               levels, mean);
    /* The reference is a sky: blue over the horizon, its rows not all alike. */
    int lo = 255, hi = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) lo = cli[4 * i + 2] < lo ? cli[4 * i + 2] : lo, hi = cli[4 * i + 2] > hi ? cli[4 * i + 2] : hi;
    HOST_CHECK(hi - lo > 40 && cli[2] > cli[0], "the CLI's reference is no sky (blue %d..%d)", lo, hi);

    /* 3. AUTO: compute where the post chain is (a GPU), fragment on a CPU implementation; without STORAGE usage,
     * fragment. FRAGMENT into the storage image: the fragment path's bytes. */
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(srgb.physical, &props);
    vksky_tonemap_path gpu_path = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? VKSKY_TONEMAP_PATH_FRAGMENT
                                                                                  : VKSKY_TONEMAP_PATH_COMPUTE;
    vksky_display_config auto_cfg = {.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG, .target_usage = STORAGE};
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &auto_cfg, NULL, &ra) == VKSKY_SUCCESS, "the AUTO renderer");
    HOST_CHECK(ra && vksky_renderer_get_tonemap_path(ra) == gpu_path, "AUTO with STORAGE: %d, expected %d",
               ra ? (int)vksky_renderer_get_tonemap_path(ra) : -1, (int)gpu_path);
    vksky_display_config plain = auto_cfg;
    plain.target_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &plain, NULL, &rn) == VKSKY_SUCCESS, "the AUTO renderer, no STORAGE");
    HOST_CHECK(rn && vksky_renderer_get_tonemap_path(rn) == VKSKY_TONEMAP_PATH_FRAGMENT, "AUTO without STORAGE");
    vksky_display_config frag_cfg = compute_cfg;
    frag_cfg.tonemap_path = VKSKY_TONEMAP_PATH_FRAGMENT;
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &frag_cfg, NULL, &rx) == VKSKY_SUCCESS, "the FRAGMENT renderer");
    if (!rx) return 1;
    HOST_CHECK(vksky_renderer_get_tonemap_path(rx) == VKSKY_TONEMAP_PATH_FRAGMENT, "FRAGMENT asked: not fragment");
    frames(&unorm, rx, VK_FORMAT_R8G8B8A8_UNORM, fragment_unorm);
    HOST_CHECK(max_difference(fragment_unorm, fragment, "FRAGMENT into the UNORM image vs the sRGB image") <= 1,
               "FRAGMENT into the UNORM image differs from the fragment path");

    /* 4. Refusals, each with one message. */
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    vksky_renderer *no = NULL;
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_SRGB, &compute_cfg, NULL, &no) == VKSKY_ERROR_UNSUPPORTED && !no,
               "COMPUTE into an sRGB format was accepted");
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &(vksky_display_config){.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG,
               .target_usage = plain.target_usage, .tonemap_path = VKSKY_TONEMAP_PATH_COMPUTE}, NULL, &no) ==
               VKSKY_ERROR_UNSUPPORTED && !no, "COMPUTE without STORAGE usage was accepted");
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_UNORM, &(vksky_display_config){.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG,
               .target_usage = STORAGE, .tonemap_path = (vksky_tonemap_path)3}, NULL, &no) ==
               VKSKY_ERROR_INVALID_ARGUMENT && !no, "a path out of range was accepted");
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    HOST_CHECK(make(c, VK_FORMAT_R8G8B8A8_SRGB, &auto_cfg, &rb, &no) == VKSKY_ERROR_INVALID_ARGUMENT && !no,
               "a display config beside a readback config was accepted");
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 4, "each refusal says why in one message (%u)",
               api_messages[VKSKY_SEVERITY_ERROR] - errors);

    vksky_renderer_destroy(rx), vksky_renderer_destroy(rn), vksky_renderer_destroy(ra);
    vksky_renderer_destroy(rc), vksky_renderer_destroy(rf), vksky_renderer_destroy(rc0), vksky_renderer_destroy(rf0);
    host_destroy_target(&unorm2), host_destroy_target(&unorm), host_destroy_target(&srgb);
    unsigned validation = vksky_context_validation_message_count(c);
    vksky_context_destroy(c);
    free(cli), free(cli_compute), free(cli_nobloom);
    HOST_CHECK(validation == 0, "%u validation messages", validation);
    if (host_failures) return 1;
    printf("api_tonemap_path: the compute tone map into a UNORM storage image equals the fragment one and the CLI\n");
    return 0;
}
