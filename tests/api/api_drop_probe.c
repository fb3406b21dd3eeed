/* The library's barriers on the host's image, proven like the CLI's (tests/barrier_drops.txt, config api): a host
 * with its own device records two DISPLAY frames into one command buffer, each followed by its own copy of the image
 * (the image's `after` use), under validation + synchronization validation. Run by tests/barrier_drop_test.sh in
 * vksky's place: `--validate` and `--trace-barriers` are its options, VKSKY_DROP_BARRIER / VKSKY_WEAKEN_BARRIER name
 * the barrier to change, messages are printed as vksky prints them and any makes the exit status 1.
 * Built from libvksky's objects (not the .so) to reach the trace and drop switches; the host's Vulkan calls go
 * through volk's table, the one the library fills from the host's vkGetInstanceProcAddr.
 * --spectral (config api_spectral, ABI 4): instead, two frames of --spectral 8 (three groups, a readback renderer
 * each) summed on the GPU (vksky_frame_spectral_sum), a command buffer a frame. */
#include <volk.h>
#include "api_host.h"
#include "gpu/barrier.h"
#include "luts_host_comp.h"

/* Two frames of three spectral groups summed on the GPU, in one command buffer (config api_spectral). */
static int spectral_frames(host *h, vksky_context *c, bool trace)
{
    enum { GROUPS = 3, SIZE = 64 };
    vksky_scene *earth = NULL, *gs[GROUPS] = {0};
    vksky_renderer *r[GROUPS] = {0};
    vksky_spectral_sum *sum = NULL;
    double w[GROUPS][4][3];
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    if (vksky_scene_create_earth(&earth) != VKSKY_SUCCESS || vksky_spectral_sum_create(c, SIZE, SIZE, &sum)) return 1;
    for (int g = 0; g < GROUPS; ++g) {
        vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .next = &rb, .output = VKSKY_OUTPUT_DISPLAY,
                                 .width = SIZE, .height = SIZE, .target_format = VK_FORMAT_R8G8B8A8_SRGB,
                                 .quality = "lesson", .bloom = true, .units = VKSKY_UNITS_RELATIVE};
        if (vksky_scene_spectral_group(earth, 8, 3, (uint32_t)g, &gs[g], w[g], NULL) != VKSKY_SUCCESS) return 1;
        d.scene = gs[g];
        if (vksky_renderer_create(c, &d, &r[g]) != VKSKY_SUCCESS) return 1;
    }
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .pitch_deg = 10.0, .fov_deg = 75.0};
    if (trace) gpu_barrier_trace(stdout);
    /* A command buffer a frame (the command line's sequences on a GPU), submitted and waited for in turn. */
    for (int frame = 0; frame < 2; ++frame) {
        if (trace) fputs("commands\n", stdout);
        host_begin(h);
        for (int g = 0; g < GROUPS; ++g) {
            vksky_frame_spectral_sum step = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM, .next = &view, .sum = sum,
                                             .group = (uint32_t)g, .first = g == 0, .last = g + 1 == GROUPS};
            memcpy(step.xyz_weights, w[g], sizeof step.xyz_weights);
            vksky_frame f = {.next = &step};
            if (vksky_record(r[g], h->cmd, &f) != VKSKY_SUCCESS) return 1;
        }
        host_end_submit_wait(h);
    }
    gpu_barrier_trace(NULL);
    for (int g = 0; g < GROUPS; ++g) vksky_renderer_destroy(r[g]), vksky_scene_destroy(gs[g]);
    vksky_spectral_sum_destroy(sum);
    vksky_scene_destroy(earth);
    vksky_context_destroy(c);
    host_destroy_target(h);
    host_destroy_device(h, NULL);
    if (host_validation_messages) fprintf(stderr, "vksky: validation reported %u messages\n", host_validation_messages);
    return host_validation_messages ? 1 : 0;
}

int main(int argc, char **argv)
{
    bool trace = false, luts = false, storage = false, spectral = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (!strcmp(argv[i], "--luts")) luts = true;   /* LUTS_ONLY, the host's shader sampling the LUTs */
        else if (!strcmp(argv[i], "--storage")) storage = true;   /* the compute tone map into a storage image */
        else if (!strcmp(argv[i], "--spectral")) spectral = true;   /* three groups summed on the GPU */
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "api_drop_probe: unknown option '%s' (accepted: --validate, --trace-barriers, --luts, "
                            "--storage, --spectral)\n",
                    argv[i]);
            return 2;
        }
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "api_drop_probe: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    if (volkInitialize() != VK_SUCCESS) return 1;
    host h;
    host_create_device(&h, NULL);
    host_create_target_usage(&h, 64, 64, VK_FORMAT_R8G8B8A8_UNORM, storage ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;
    if (spectral) return spectral_frames(&h, c, trace);
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION,
                             .output = luts ? VKSKY_OUTPUT_LUTS_ONLY : VKSKY_OUTPUT_DISPLAY, .width = 64,
                             .height = 64, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "lesson",
                             .bloom = true, .units = VKSKY_UNITS_RELATIVE};
    vksky_display_config dc = {.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG, .tonemap_path = VKSKY_TONEMAP_PATH_COMPUTE,
                               .target_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                               VK_IMAGE_USAGE_STORAGE_BIT};
    if (storage) d.next = &dc;
    vksky_renderer *r = NULL;
    if (vksky_renderer_create(c, &d, &r) != VKSKY_SUCCESS) return 1;
    if (storage && vksky_renderer_get_tonemap_path(r) != VKSKY_TONEMAP_PATH_COMPUTE) return 1;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 1.0, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(&h, VK_FORMAT_R8G8B8A8_UNORM)};
    host_luts pass;
    vksky_luts l;
    if (luts && (vksky_get_luts(r, &l) != VKSKY_SUCCESS)) return 1;
    if (luts) host_luts_create(&h, &pass, &l, spv_luts_host, sizeof spv_luts_host, 64);
    if (trace) gpu_barrier_trace(stdout);
    host_begin(&h);
    for (int frame = 0; frame < 2; ++frame) {
        if (frame > 0) host_buffer_waw(&h, luts ? pass.buffer : h.buffer);   /* the host's own: two copies, one buffer */
        f.force_luts = frame > 0;   /* the second frame's LUT passes after the first frame's reads */
        if (vksky_record(r, h.cmd, &f) != VKSKY_SUCCESS) return 1;
        gpu_barrier_trace_pass(luts ? "host luts pass" : "host copy");   /* the host's own pass, for the trace */
        if (luts) host_luts_record(&h, &pass);
        else if (frame == 0) host_copy(&h);
    }
    if (luts) host_submit(&h, pass.buffer);
    else host_end_and_read(&h);
    if (luts) host_luts_destroy(&h, &pass);
    gpu_barrier_trace(NULL);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    if (host_validation_messages) fprintf(stderr, "vksky: validation reported %u messages\n", host_validation_messages);
    return host_validation_messages ? 1 : 0;
}
