/* A sequence through the public API (issue 25 item 1), as a host renders one: the scene of an animated command line
 * (vksky_scene_from_args), each frame's animated values set as numbers (vksky_scene_set_values), the renderer given
 * that scene (vksky_renderer_set_scene), two frames in flight in two command buffers of the host's, each copied into
 * its own readback slot (vksky_readback_target) and read after both finished. Checked:
 *   - every frame's display pixels equal, byte for byte, the PNG of the same frame from `vksky --render` of that
 *     sequence (the command line's sequence), and the PNG of a single `vksky --render` with the animated values given
 *     as plain flags (`--sun-elevation 14 --yaw 30`: a sequence frame is the frame of those flags, docs/sequences.md);
 *   - two frames in flight do not share a readback buffer (frame 0's slot still holds frame 0 after frame 1);
 *   - vksky_renderer_scene_changes: false for a frame that moves only the view (no host wait needed), true when the
 *     sun's height changes the light the uniform block holds;
 *   - refusals: a flag the command line does not animate, a readback slot past the renderer's, slots on a renderer
 *     without readback; one message each.
 * Validation + synchronization validation on throughout (the test's context and every CLI run); any message fails. */
#include "api_host.h"
#include "io/png_io.h"
#include <stdint.h>

#define W 48
#define H 27
#define FRAMES 3

static const char *vksky_bin, *dir;

/* The command line of the sequence (the PNG pattern is the CLI's; the API writes nothing). */
static char *seq_argv[] = {"vksky", "--width", "48", "--height", "27", "--quality", "medium", "--pitch", "8", "--fov", "60",
                           "--frame-count", "3", "--animate", "sun-elevation=-2:30", "--animate", "yaw=0:60",
                           "--render", "unused_%d.png"};

static uint8_t *read_png(const char *path)
{
    int w = 0, h = 0;
    uint8_t *rgba = NULL;
    char err[200];
    if (io_read_png(path, &w, &h, &rgba, err, sizeof err) != 0 || w != W || h != H) {
        fprintf(stderr, "FAIL: %s: %s\n", path, err);
        exit(1);
    }
    return rgba;
}

static void run(const char *args)
{
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "%s %s --validate --quiet", vksky_bin, args);
    if (system(cmd) != 0) {
        fprintf(stderr, "FAIL: %s\n", cmd);
        exit(1);
    }
}

/* Frame i's animated values, as the command line's sequence makes them (linear from FROM at frame 0 to TO). */
static void frame_values(int i, double values[2])
{
    double t = (double)i / (FRAMES - 1);
    values[0] = (1.0 - t) * -2.0 + t * 30.0, values[1] = (1.0 - t) * 0.0 + t * 60.0;
}

static void record(vksky_renderer *r, VkCommandBuffer cmd, int i, uint32_t slot)
{
    double v[2];
    frame_values(i, v);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    HOST_VK(vkResetCommandBuffer(cmd, 0));
    HOST_VK(vkBeginCommandBuffer(cmd, &bi));
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = v[1], .pitch_deg = 8.0, .fov_deg = 60.0};
    vksky_readback_target target = {.type = VKSKY_STRUCTURE_TYPE_READBACK_TARGET, .next = &view, .slot = slot};
    /* A photometric PNG is auto-exposed: metered on the GPU, the result beside the slot. */
    vksky_auto_exposure metered = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, .next = &target, .slot = slot};
    vksky_frame f = {.next = &metered};
    vksky_result res = vksky_record(r, cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record frame %d: %s", i, vksky_result_name(res));
    HOST_VK(vkEndCommandBuffer(cmd));
}

static void submit(VkQueue queue, VkCommandBuffer cmd, VkFence fence)
{
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci};
    HOST_VK(vkQueueSubmit2(queue, 1, &si, fence));
}

static void set_frame(vksky_scene *scene, vksky_renderer *r, int i, bool *changes)
{
    const char *flags[2] = {"--sun-elevation", "--yaw"};
    double v[2];
    frame_values(i, v);
    vksky_result res = vksky_scene_set_values(scene, 2, flags, v, api_message, NULL);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_scene_set_values frame %d: %s", i, vksky_result_name(res));
    *changes = vksky_renderer_scene_changes(r, scene);
    res = vksky_renderer_set_scene(r, scene);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_set_scene frame %d: %s", i, vksky_result_name(res));
}

static void check_frame(const uint8_t *px, int i)
{
    char path[600], args[1000];
    double v[2];
    frame_values(i, v);
    snprintf(path, sizeof path, "%s/seq_%d.png", dir, i);
    uint8_t *cli = read_png(path);
    HOST_CHECK(!memcmp(cli, px, 4 * (size_t)W * H), "frame %d differs from the command line's sequence", i);
    free(cli);
    snprintf(path, sizeof path, "%s/single_%d.png", dir, i);
    snprintf(args, sizeof args, "--width 48 --height 27 --quality medium --pitch 8 --fov 60 --sun-elevation %.17g --yaw %.17g "
             "--render %s", v[0], v[1], path);
    run(args);
    cli = read_png(path);
    HOST_CHECK(!memcmp(cli, px, 4 * (size_t)W * H), "frame %d differs from a single render of its values", i);
    free(cli);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: api_sequence VKSKY_BIN WORK_DIR\n");
        return 2;
    }
    vksky_bin = argv[1], dir = argv[2];
    /* The command line's sequence, its PNGs beside the test's. */
    char args[1000];
    snprintf(args, sizeof args, "--width 48 --height 27 --quality medium --pitch 8 --fov 60 --frame-count 3 --animate "
             "sun-elevation=-2:30 --animate yaw=0:60 --render %s/seq_%%d.png", dir);
    run(args);

    vksky_context *c = host_own_context();
    vksky_scene *scene = host_scene_of_args((int)(sizeof seq_argv / sizeof *seq_argv), seq_argv);
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc d = host_readback_desc(&rb, scene, W, H, true);
    vksky_renderer *r = host_renderer(c, &d);
    vksky_result res = vksky_renderer_set_readback_slots(r, 2);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_set_readback_slots 2: %s", vksky_result_name(res));

    /* The host's two command buffers and fences (a ring of two). */
    vksky_context_handles k;
    vksky_context_get_handles(c, &k);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = k.queue_family};
    VkCommandPool pool;
    HOST_VK(vkCreateCommandPool(k.device, &pi, NULL, &pool));
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 2};
    VkCommandBuffer cmd[2];
    HOST_VK(vkAllocateCommandBuffers(k.device, &ai, cmd));
    VkFence fence[2];
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    for (int s = 0; s < 2; ++s) HOST_VK(vkCreateFence(k.device, &fi, NULL, &fence[s]));

    /* Frame 0 (its scene applied: the first, a change), then frame 1 recorded and submitted while frame 0 may still
     * run: its scene changes the sun's light, so the host waits for frame 0 before setting it (the ring's drain). */
    bool changes = false;
    set_frame(scene, r, 0, &changes);
    record(r, cmd[0], 0, 0);
    submit(k.queue, cmd[0], fence[0]);
    const char *flags[2] = {"--sun-elevation", "--yaw"};
    double v1[2];
    frame_values(1, v1);
    HOST_CHECK(vksky_scene_set_values(scene, 2, flags, v1, api_message, NULL) == VKSKY_SUCCESS, "set_values 1");
    HOST_CHECK(vksky_renderer_scene_changes(r, scene), "frame 1's sun (another height, other light): no change seen");
    HOST_VK(vkWaitForFences(k.device, 1, &fence[0], VK_TRUE, UINT64_MAX));
    set_frame(scene, r, 1, &changes);
    record(r, cmd[1], 1, 1);
    submit(k.queue, cmd[1], fence[1]);
    HOST_VK(vkWaitForFences(k.device, 2, fence, VK_TRUE, UINT64_MAX));
    vksky_readback px[2];
    for (uint32_t s = 0; s < 2; ++s) {
        res = vksky_renderer_get_readback_slot(r, s, &px[s]);
        HOST_CHECK(res == VKSKY_SUCCESS && px[s].width == W && px[s].height == H, "get_readback_slot %u", s);
    }
    HOST_CHECK(px[0].display_rgba8 != px[1].display_rgba8, "two slots, one buffer");
    check_frame(px[0].display_rgba8, 0);   /* slot 0 still holds frame 0 after frame 1 was copied into slot 1 */
    check_frame(px[1].display_rgba8, 1);

    /* Frame 2 into slot 0 again, its fence reset (the host's ring reuses a slot once it has read it). */
    HOST_VK(vkResetFences(k.device, 2, fence));
    set_frame(scene, r, 2, &changes);
    record(r, cmd[0], 2, 0);
    submit(k.queue, cmd[0], fence[0]);
    HOST_VK(vkWaitForFences(k.device, 1, &fence[0], VK_TRUE, UINT64_MAX));
    HOST_CHECK(vksky_renderer_get_readback_slot(r, 0, &px[0]) == VKSKY_SUCCESS, "get_readback_slot 0");
    check_frame(px[0].display_rgba8, 2);

    /* A frame that moves only the view: nothing the GPU reads of the scene changes (no host wait needed). */
    const char *yaw[1] = {"--yaw"};
    double other_yaw = 10.0;
    HOST_CHECK(vksky_scene_set_values(scene, 1, yaw, &other_yaw, api_message, NULL) == VKSKY_SUCCESS, "set yaw");
    HOST_CHECK(!vksky_renderer_scene_changes(r, scene), "a new yaw reported as a scene change");

    /* Refusals, one message each. */
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    const char *not_animated[1] = {"--altitude"};
    double one = 1.0;
    HOST_CHECK(vksky_scene_set_values(scene, 1, not_animated, &one, api_message, NULL) == VKSKY_ERROR_INVALID_ARGUMENT,
               "a flag the command line does not animate accepted");
    HOST_CHECK(vksky_renderer_set_readback_slots(r, VKSKY_READBACK_SLOTS_MAX + 1) == VKSKY_ERROR_INVALID_ARGUMENT,
               "too many readback slots accepted");
    HOST_CHECK(vksky_renderer_get_readback_slot(r, 2, &px[0]) == VKSKY_ERROR_INVALID_ARGUMENT, "slot 2 of 2 read");
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = 0, .pitch_deg = 8.0, .fov_deg = 60.0};
    vksky_readback_target past = {.type = VKSKY_STRUCTURE_TYPE_READBACK_TARGET, .next = &view, .slot = 2};
    vksky_frame f = {.next = &past, .exposure = 12.0};
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    HOST_VK(vkResetCommandBuffer(cmd[1], 0));
    HOST_VK(vkBeginCommandBuffer(cmd[1], &bi));
    HOST_CHECK(vksky_record(r, cmd[1], &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a readback slot past the last recorded");
    vkEndCommandBuffer(cmd[1]);
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 3, "%u error messages for 3 refusals with messages",
               api_messages[VKSKY_SEVERITY_ERROR] - errors);

    vkDeviceWaitIdle(k.device);
    for (int s = 0; s < 2; ++s) vkDestroyFence(k.device, fence[s], NULL);
    vkDestroyCommandPool(k.device, pool, NULL);
    vksky_renderer_destroy(r);
    vksky_scene_destroy(scene);
    HOST_CHECK(vksky_context_validation_message_count(c) == 0, "%u validation messages",
               vksky_context_validation_message_count(c));
    vksky_context_destroy(c);
    return host_failures ? 1 : 0;
}
