/* The LUTs on the host's compute queue through the API (issue 25 item 4, ABI 2): a host device (validation +
 * synchronization validation; any message fails) whose compute queue is its graphics queue (lavapipe has one queue:
 * the same family, so no ownership transfer; the other-family path is tools/async_bench.sh's on a GPU).
 *  - a DISPLAY frame with the LUTs built in its own command buffer (vksky_record, force_luts) is the reference;
 *  - vksky_record_luts(force) into a second command buffer, submitted signalling the host's timeline semaphore 1,
 *    then vksky_record into the frame's command buffer, submitted waiting for >= 1 at vksky_luts.ready_stage: the
 *    image is byte-identical;
 *  - vksky_record_luts with the LUTs up to date records nothing (recorded = false); a NULL command buffer is
 *    VKSKY_ERROR_INVALID_ARGUMENT; the context's handles report the compute queue. */
#include "api_host.h"

/* The frame's copy read back, its submission waiting for `wait` >= `value` at `stage` (none when VK_NULL_HANDLE). */
static unsigned char *read_frame(host *h, VkSemaphore wait, uint64_t value, VkPipelineStageFlags2 stage)
{
    host_copy(h);
    host_submit_waiting(h, h->buffer, wait, value, stage);
    size_t n = 4ull * h->width * h->height;
    unsigned char *out = malloc(n);
    if (out) memcpy(out, h->mapped, n);
    return out;
}

int main(void)
{
    host h;
    host_create_device(&h, NULL);
    host_create_target(&h, 48, 32, VK_FORMAT_R8G8B8A8_UNORM);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    cd.compute_queue = true, cd.compute_queue_family = h.family, cd.compute_queue_index = h.index;
    vksky_context *c = NULL;
    HOST_CHECK(vksky_context_create(&cd, &c) == VKSKY_SUCCESS, "context with a compute queue");
    if (!c) return 1;
    vksky_context_handles hd;
    vksky_context_get_handles(c, &hd);
    HOST_CHECK(hd.compute_queue == h.queue && hd.compute_queue_family == h.family, "handles: the compute queue");
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = 48,
                             .height = 32, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "lesson",
                             .bloom = true, .units = VKSKY_UNITS_RELATIVE};
    vksky_renderer *r = NULL;
    HOST_CHECK(vksky_renderer_create(c, &d, &r) == VKSKY_SUCCESS, "renderer");
    if (!r) return 1;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 1.5, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(&h, VK_FORMAT_R8G8B8A8_UNORM), .force_luts = true};

    host_begin(&h);
    HOST_CHECK(vksky_record(r, h.cmd, &f) == VKSKY_SUCCESS, "the reference frame");
    unsigned char *want = read_frame(&h, VK_NULL_HANDLE, 0, 0);

    VkSemaphoreTypeCreateInfo type = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                      .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE};
    VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &type};
    VkSemaphore luts_done;
    HOST_VK(vkCreateSemaphore(h.device, &sci, NULL, &luts_done));
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = h.pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer lc;
    HOST_VK(vkAllocateCommandBuffers(h.device, &ai, &lc));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    HOST_VK(vkBeginCommandBuffer(lc, &bi));
    bool recorded = false;
    HOST_CHECK(vksky_record_luts(r, lc, true, &recorded) == VKSKY_SUCCESS && recorded, "vksky_record_luts(force)");
    HOST_VK(vkEndCommandBuffer(lc));
    /* The LUTs' submission signals 1; the frame's waits for it where the LUTs are first read. */
    VkSemaphoreSubmitInfo s = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = luts_done, .value = 1,
                               .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = lc};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci,
                        .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &s};
    HOST_VK(vkQueueSubmit2(hd.compute_queue, 1, &si, VK_NULL_HANDLE));
    f.force_luts = false;
    host_begin(&h);
    HOST_CHECK(vksky_record(r, h.cmd, &f) == VKSKY_SUCCESS, "the frame after vksky_record_luts");
    vksky_luts l;
    HOST_CHECK(vksky_get_luts(r, &l) == VKSKY_SUCCESS, "vksky_get_luts");
    unsigned char *got = read_frame(&h, luts_done, 1, l.ready_stage);
    HOST_CHECK(want && got && !memcmp(want, got, 4ull * 48 * 32),
               "the frame with the LUTs from vksky_record_luts differs from the one-command-buffer frame");

    /* Up to date: nothing recorded. */
    HOST_VK(vkResetCommandBuffer(lc, 0));
    HOST_VK(vkBeginCommandBuffer(lc, &bi));
    HOST_CHECK(vksky_record_luts(r, lc, false, &recorded) == VKSKY_SUCCESS && !recorded,
               "vksky_record_luts with the LUTs up to date recorded something");
    HOST_VK(vkEndCommandBuffer(lc));
    HOST_CHECK(vksky_record_luts(r, VK_NULL_HANDLE, true, &recorded) == VKSKY_ERROR_INVALID_ARGUMENT,
               "a NULL command buffer");

    vkDeviceWaitIdle(h.device);
    vkFreeCommandBuffers(h.device, h.pool, 1, &lc);
    vkDestroySemaphore(h.device, luts_done, NULL);
    free(want);
    free(got);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    if (host_failures) return 1;
    printf("api_async: ok\n");
    return 0;
}
