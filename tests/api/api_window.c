/* ABI 3, what the window needs of the API (issue 25, task 25m), each against an independent path:
 *  - vksky_frame_display: a frame with the operator and bloom switched per frame (renderer made with bloom, scene ACES)
 *    equals, byte for byte, a frame of a renderer whose command line says --tonemap reinhard and has no bloom chain;
 *    switched back, the frame equals the renderer's own frame without the extension;
 *  - vksky_frame_place: a frame at altitude 3 km with the sun at (40, 7) given per frame equals the frame of a scene
 *    whose command line says --altitude 3 --sun-azimuth 40 --sun-elevation 7, byte for byte;
 *  - vksky_frame_timer: two frames in flight (two command buffers submitted together) in timer slots 0 and 1, one
 *    with bloom and one without, read after both completed: slot 0 holds the bloom passes, slot 1 none; a slot is
 *    read once;
 *  - vksky_frame_capture: the capture buffer's bytes equal the host's own copy of the same image (and of a swapchain
 *    frame's image, captured before it goes to PRESENT_SRC); the trace has display.write_to_capture, capture.to_host;
 *  - vksky_frame_swapchain: the trace names the window's display.to_attachment / display.to_present, no host.color;
 *  - each extension's wrong use is refused with VKSKY_ERROR_INVALID_ARGUMENT and one message.
 * Validation and synchronization validation on: any message fails the test. */
#include "api_host.h"
#include <stdint.h>

#define W 64u
#define H 36u
#define FMT VK_FORMAT_R8G8B8A8_SRGB

static struct { char lines[2048][160]; int count; } trace;
static void on_trace(void *user, const char *line)
{
    (void)user;
    if (trace.count < 2048) snprintf(trace.lines[trace.count++], sizeof trace.lines[0], "%s", line);
}
static int traced(const char *name)
{
    int n = 0;
    for (int i = 0; i < trace.count; ++i) n += strstr(trace.lines[i], name) != NULL;
    return n;
}

static vksky_renderer *renderer_of(vksky_context *c, int argc, char **argv, bool bloom)
{
    vksky_scene *scene = host_scene_of_args(argc, argv);
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = W, .height = H,
                             .target_format = FMT, .quality = "scene", .bloom = bloom,
                             .units = VKSKY_UNITS_PHOTOMETRIC, .scene = scene};
    vksky_renderer *r = host_renderer(c, &d);
    vksky_scene_destroy(scene);
    return r;
}

/* One frame into the host's image, copied by the host and waited for: its bytes (malloc'd). */
static uint8_t *shot(host *h, vksky_renderer *r, const void *next)
{
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .next = next, .yaw_deg = 10, .pitch_deg = 5,
                             .fov_deg = 75};
    vksky_frame f = {.next = &view, .exposure = 12, .color = host_image(h, FMT)};
    host_begin(h);
    vksky_result res = vksky_record(r, h->cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
    host_end_and_read(h);
    uint8_t *out = malloc(4 * (size_t)W * H);
    memcpy(out, h->mapped, 4 * (size_t)W * H);
    return out;
}

static size_t differing(const uint8_t *a, const uint8_t *b)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) n += memcmp(a + 4 * i, b + 4 * i, 4) != 0;
    return n;
}

/* A frame chaining `next` (after a vksky_frame_view, unless `no_view`) refused with one message. */
static void expect_refused(vksky_renderer *r, host *h, const void *next, bool no_view, const char *what)
{
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .next = next, .yaw_deg = 0, .pitch_deg = 5,
                             .fov_deg = 75};
    vksky_frame f = {.next = no_view ? next : (const void *)&view, .exposure = 12, .color = host_image(h, FMT)};
    host_begin(h);
    vksky_result res = vksky_record(r, h->cmd, &f);
    vkEndCommandBuffer(h->cmd);
    HOST_CHECK(res == VKSKY_ERROR_INVALID_ARGUMENT, "%s: %s, expected VKSKY_ERROR_INVALID_ARGUMENT", what,
               vksky_result_name(res));
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 1, "%s: %u messages, expected one", what,
               api_messages[VKSKY_SEVERITY_ERROR] - errors);
}

int main(void)
{
    /* PRESENT_SRC_KHR needs VK_KHR_swapchain, which needs VK_KHR_surface (no surface is made). */
    const char *surface = "VK_KHR_surface";
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .validation = true,
                                .instance_extensions = &surface, .instance_extension_count = 1, .swapchain = true,
                                .message = api_message};
    vksky_context *c = NULL;
    vksky_result res = vksky_context_create_own(&od, &c);
    HOST_CHECK(res == VKSKY_SUCCESS && c, "vksky_context_create_own: %s", vksky_result_name(res));
    if (!c) return 1;
    host h;
    host_from_context(&h, c);
    host_create_target(&h, W, H, FMT);

    /* 1. The tone map operator and bloom per frame. */
    char *aces[] = {"vksky", "--quality", "low", "--sun-elevation", "4"};
    char *reinhard[] = {"vksky", "--quality", "low", "--sun-elevation", "4", "--tonemap", "reinhard"};
    vksky_renderer *live = renderer_of(c, 5, aces, true), *ref = renderer_of(c, 7, reinhard, false);
    vksky_frame_display off = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .tonemap = VKSKY_TONEMAP_OPERATOR_REINHARD,
                               .bloom = false};
    vksky_frame_display on = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .tonemap = VKSKY_TONEMAP_OPERATOR_ACES,
                              .bloom = true};
    uint8_t *plain = shot(&h, live, NULL), *switched = shot(&h, live, &off), *expected = shot(&h, ref, NULL);
    uint8_t *back = shot(&h, live, &on);
    size_t d_sw = differing(switched, expected), d_back = differing(back, plain), d_ctl = differing(plain, expected);
    printf("display: reinhard, no bloom per frame vs --tonemap reinhard --no-bloom: %zu pixels differ; switched back "
           "vs the scene's ACES + bloom: %zu; ACES + bloom vs reinhard: %zu (of %u)\n", d_sw, d_back, d_ctl, W * H);
    HOST_CHECK(d_sw == 0 && d_back == 0, "per-frame tone map / bloom: %zu, %zu pixels differ", d_sw, d_back);
    HOST_CHECK(d_ctl > W * H / 4, "the operators are too alike to test (%zu pixels)", d_ctl);
    free(plain), free(switched), free(expected), free(back);

    /* 2. The camera's altitude and the sun per frame, beside vksky_frame_view. */
    char *high[] = {"vksky", "--quality", "low", "--altitude", "3", "--sun-azimuth", "40", "--sun-elevation", "7"};
    vksky_renderer *placed = renderer_of(c, 9, high, true);
    vksky_frame_display aces_on = on;
    uint8_t *moved = shot(&h, live, &(vksky_frame_place){.type = VKSKY_STRUCTURE_TYPE_FRAME_PLACE, .next = &aces_on,
                                                         .altitude_km = 3, .sun_azimuth_deg = 40,
                                                         .sun_elevation_deg = 7});
    uint8_t *there = shot(&h, placed, NULL), *ground = shot(&h, live, NULL);
    size_t d_place = differing(moved, there), d_ground = differing(ground, there);
    printf("place: altitude 3 km, sun (40, 7) per frame vs --altitude 3 --sun-azimuth 40 --sun-elevation 7: %zu pixels "
           "differ; the scene's own place vs that: %zu\n", d_place, d_ground);
    HOST_CHECK(d_place == 0, "per-frame place: %zu pixels differ", d_place);
    HOST_CHECK(d_ground > W * H / 4, "the places are too alike to test (%zu pixels)", d_ground);
    free(moved), free(there), free(ground);

    /* 3. Timers of two frames in flight: slot 0 with bloom, slot 1 without, read after both completed. */
    VkCommandBuffer second;
    VkCommandBufferAllocateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = h.pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    HOST_VK(vkAllocateCommandBuffers(h.device, &ci, &second));
    VkCommandBuffer cmds[2] = {h.cmd, second};
    for (uint32_t s = 0; s < 2; ++s) {
        vksky_frame_timer timer = {.type = VKSKY_STRUCTURE_TYPE_FRAME_TIMER, .slot = s};
        vksky_frame_display disp = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .next = &timer,
                                    .tonemap = VKSKY_TONEMAP_OPERATOR_ACES, .bloom = s == 0};
        vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .next = &disp, .pitch_deg = 5, .fov_deg = 75};
        vksky_frame f = {.next = &view, .exposure = 12, .color = host_image(&h, FMT)};
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        HOST_VK(vkResetCommandBuffer(cmds[s], 0));
        HOST_VK(vkBeginCommandBuffer(cmds[s], &bi));
        res = vksky_record(live, cmds[s], &f);
        HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record (timer slot %u): %s", s, vksky_result_name(res));
        HOST_VK(vkEndCommandBuffer(cmds[s]));
    }
    VkCommandBufferSubmitInfo cs[2] = {{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmds[0]},
                                       {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmds[1]}};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 2, .pCommandBufferInfos = cs};
    HOST_VK(vkQueueSubmit2(h.queue, 1, &si, h.fence));
    HOST_VK(vkWaitForFences(h.device, 1, &h.fence, VK_TRUE, UINT64_MAX));
    HOST_VK(vkResetFences(h.device, 1, &h.fence));
    for (uint32_t s = 0; s < 2; ++s) {
        vksky_pass_timing t[32];
        uint32_t n = 0, blooms = 0, skies = 0;
        res = vksky_renderer_get_slot_timings(live, s, t, 32, &n);
        HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_get_slot_timings(%u): %s", s, vksky_result_name(res));
        for (uint32_t i = 0; i < n && i < 32; ++i) {
            blooms += !strncmp(t[i].name, "bloom", 5), skies += !strcmp(t[i].name, "sky");
            HOST_CHECK(t[i].gpu_ms >= 0.0 && t[i].gpu_ms < 10000.0, "slot %u pass %s: %g ms", s, t[i].name, t[i].gpu_ms);
        }
        printf("timer slot %u: %u passes, %u of bloom\n", s, n, blooms);
        HOST_CHECK(skies == 1 && (s == 0 ? blooms > 0 : blooms == 0), "slot %u: %u sky, %u bloom passes", s, skies, blooms);
        uint32_t again = 1;
        vksky_renderer_get_slot_timings(live, s, t, 32, &again);
        HOST_CHECK(again == 0, "slot %u read twice gave %u passes", s, again);
    }
    vkFreeCommandBuffers(h.device, h.pool, 1, &second);

    /* 4, 5. The capture, into the host's image and into a swapchain-used image, traced. */
    vksky_context_set_trace(c, VKSKY_TRACE_BARRIERS, on_trace, NULL);
    vksky_frame_capture capture = {.type = VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE};
    uint8_t *copied = shot(&h, live, &capture);
    vksky_readback cap;
    res = vksky_renderer_get_capture(live, &cap);
    HOST_CHECK(res == VKSKY_SUCCESS && cap.display_rgba8 && cap.width == W && cap.height == H,
               "vksky_renderer_get_capture: %s", vksky_result_name(res));
    size_t d_cap = res == VKSKY_SUCCESS ? differing(cap.display_rgba8, copied) : W * H;
    HOST_CHECK(traced("display.write_to_capture") == 1 && traced("capture.to_host") == 1 &&
               traced("host.color.to_after") == 1, "the capture frame's trace lacks its barriers");
    trace.count = 0;
    vksky_frame_swapchain sc = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN, .next = &capture};
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .next = &sc, .yaw_deg = 10, .pitch_deg = 5,
                             .fov_deg = 75};
    vksky_frame f = {.next = &view, .exposure = 12, .color = host_image(&h, FMT)};
    host_begin(&h);
    res = vksky_record(live, h.cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record (swapchain): %s", vksky_result_name(res));
    host_end_submit_wait(&h);
    res = vksky_renderer_get_capture(live, &cap);
    size_t d_sc = res == VKSKY_SUCCESS ? differing(cap.display_rgba8, copied) : W * H;
    printf("capture vs the host's copy: %zu pixels differ; a swapchain frame's capture: %zu\n", d_cap, d_sc);
    HOST_CHECK(d_cap == 0 && d_sc == 0, "captures: %zu, %zu pixels differ", d_cap, d_sc);
    HOST_CHECK(traced("display.to_attachment") == 1 && traced("display.to_present") == 1 && traced("host.color") == 0 &&
               traced("display.write_to_capture") == 1, "the swapchain frame's barrier names: %d %d %d",
               traced("display.to_attachment"), traced("display.to_present"), traced("host.color"));
    vksky_context_set_trace(c, 0, NULL, NULL);
    free(copied);
    /* The image is in PRESENT_SRC now; the frames below start from UNDEFINED (host_image's `before`), as any may. */

    /* 6. Wrong uses. */
    vksky_frame_display bloom_on = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .bloom = true};
    expect_refused(ref, &h, &bloom_on, false, "bloom on a renderer without its chain");
    vksky_frame_display bad_op = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .tonemap = (vksky_tonemap)7};
    expect_refused(live, &h, &bad_op, false, "an unknown operator");
    vksky_frame_place alone = {.type = VKSKY_STRUCTURE_TYPE_FRAME_PLACE, .altitude_km = 1.0};
    expect_refused(live, &h, &alone, true, "a place without a view");
    vksky_frame_place below = {.type = VKSKY_STRUCTURE_TYPE_FRAME_PLACE, .altitude_km = -1.0};
    expect_refused(live, &h, &below, false, "a place below the ground");
    vksky_frame_timer far = {.type = VKSKY_STRUCTURE_TYPE_FRAME_TIMER, .slot = VKSKY_TIMER_SLOTS};
    expect_refused(live, &h, &far, false, "a timer slot out of range");
    uint32_t n = 0;
    HOST_CHECK(vksky_renderer_get_slot_timings(live, VKSKY_TIMER_SLOTS, NULL, 0, &n) == VKSKY_ERROR_INVALID_ARGUMENT,
               "get_slot_timings of slot %u", VKSKY_TIMER_SLOTS);
    HOST_CHECK(vksky_renderer_get_capture(ref, &cap) == VKSKY_ERROR_INVALID_ARGUMENT, "a capture never made was given");
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_scene *scene = host_scene_of_args(5, aces);
    vksky_renderer *headless = host_renderer(c, &(vksky_renderer_desc){
        .abi_version = VKSKY_ABI_VERSION, .next = &rb, .output = VKSKY_OUTPUT_DISPLAY, .width = W, .height = H,
        .target_format = FMT, .quality = "scene", .bloom = true, .units = VKSKY_UNITS_PHOTOMETRIC, .scene = scene});
    expect_refused(headless, &h, &capture, false, "a capture on a readback renderer");

    /* 7. A readback renderer takes this frame's bloom switch (the command line's spectral groups render a bloom-free
     * frame for the host's meter, app/runs/spectral_host.c): off, its composite is bit for bit a renderer's made
     * without bloom; with the scene's (on), it is not. */
    vksky_renderer *bare = host_renderer(c, &(vksky_renderer_desc){
        .abi_version = VKSKY_ABI_VERSION, .next = &rb, .output = VKSKY_OUTPUT_DISPLAY, .width = W, .height = H,
        .target_format = FMT, .quality = "scene", .bloom = false, .units = VKSKY_UNITS_PHOTOMETRIC, .scene = scene});
    vksky_frame_view at = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = 0, .pitch_deg = 5, .fov_deg = 75};
    vksky_frame_display no_bloom = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY, .next = &at,
                                    .tonemap = VKSKY_TONEMAP_OPERATOR_ACES, .bloom = false};
    size_t bytes = (size_t)W * H * 4 * sizeof(uint16_t);
    uint16_t *linear[3];
    vksky_renderer *order[3] = {headless, headless, bare};
    const void *chains[3] = {&no_bloom, &at, &at};
    for (int k = 0; k < 3; ++k) {
        vksky_frame f = {.next = chains[k], .exposure = 12};
        host_begin(&h);
        HOST_CHECK(vksky_record(order[k], h.cmd, &f) == VKSKY_SUCCESS, "readback frame %d refused", k);
        host_end_submit_wait(&h);
        vksky_readback px = {0};
        HOST_CHECK(vksky_renderer_get_readback(order[k], &px) == VKSKY_SUCCESS && px.linear_rgba16f, "readback %d", k);
        linear[k] = malloc(bytes);
        if (px.linear_rgba16f && linear[k]) memcpy(linear[k], px.linear_rgba16f, bytes);
    }
    size_t off_vs_bare = 0, on_vs_bare = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i)
        off_vs_bare += memcmp(linear[0] + 4 * i, linear[2] + 4 * i, 8) != 0,
            on_vs_bare += memcmp(linear[1] + 4 * i, linear[2] + 4 * i, 8) != 0;
    printf("readback renderer, bloom off for a frame vs made without bloom: %zu pixels differ; the scene's bloom: %zu\n",
           off_vs_bare, on_vs_bare);
    HOST_CHECK(off_vs_bare == 0 && on_vs_bare > (size_t)W * H / 2, "bloom switch on a readback renderer: %zu, %zu",
               off_vs_bare, on_vs_bare);
    for (int k = 0; k < 3; ++k) free(linear[k]);
    vksky_renderer_destroy(bare);

    vksky_renderer_destroy(headless);
    vksky_scene_destroy(scene);
    vksky_renderer_destroy(live);
    vksky_renderer_destroy(ref);
    vksky_renderer_destroy(placed);
    host_destroy_target(&h);
    unsigned validation = vksky_context_validation_message_count(c);
    vksky_context_destroy(c);
    HOST_CHECK(validation == 0, "%u validation messages", validation);
    if (host_failures) fprintf(stderr, "api_window: %d failure(s)\n", host_failures);
    else printf("api_window: ok\n");
    return host_failures ? 1 : 0;
}
