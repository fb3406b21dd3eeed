/* The LUTs' queue-family ownership transfer through the API (tests/qfot_drops.txt, config api_async;
 * docs/synchronization.md §10): a host with its own device, its graphics queue and queue 0 of a compute-only family,
 * gives vksky both (vksky_context_desc.compute_queue_family). Two frames, each rebuilding the LUTs: vksky_record_luts
 * into the compute family's command buffer (ending with the release barriers), submitted signalling the host's
 * timeline `luts_done`; vksky_record into the graphics command buffer (beginning with the acquires), submitted
 * waiting for it at vksky_luts.ready_stage and signalling `frames_done`, which the next rebuild waits for.
 * Run by tests/barrier_drop_test.sh in vksky's place, as api_drop_probe is: `--validate` / `--trace-barriers`,
 * VKSKY_DROP_BARRIER, messages printed as vksky prints them, exit 1 on any. A device without a compute-only family
 * (lavapipe) has no transfer to record: exit 77 with one line. */
#include <volk.h>
#include "api_host.h"
#include "gpu/barrier.h"

/* One submission: `cmd` on `queue`, waiting for `wait` >= wait_value at `stage` (none when wait_value is 0),
 * signalling `signal` = signal_value; `fence` optional. A submission the validation layer refuses (a missing half of
 * the transfer is found at submission: VK_ERROR_VALIDATION_FAILED_EXT, nothing executed) has its value signalled
 * from the host instead, so that the next frame still runs and the layer sees its submissions too (an acquire's
 * absence shows only at the next release). Returns whether it was submitted. */
static bool submit(VkDevice device, VkQueue queue, VkCommandBuffer cmd, VkSemaphore wait, uint64_t wait_value,
                   VkPipelineStageFlags2 stage, VkSemaphore signal, uint64_t signal_value, VkFence fence)
{
    VkSemaphoreSubmitInfo w = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = wait,
                               .value = wait_value, .stageMask = stage};
    VkSemaphoreSubmitInfo s = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = signal,
                               .value = signal_value, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo c = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = wait_value ? 1 : 0,
                        .pWaitSemaphoreInfos = &w, .commandBufferInfoCount = 1, .pCommandBufferInfos = &c,
                        .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &s};
    VkResult res = vkQueueSubmit2(queue, 1, &si, fence);
    if (res == VK_SUCCESS) return true;
    fprintf(stderr, "api_qfot_probe: a submission was refused (VkResult %d)\n", (int)res);
    VkSemaphoreSignalInfo host_signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO, .semaphore = signal,
                                         .value = signal_value};
    HOST_VK(vkSignalSemaphore(device, &host_signal));
    return false;
}

static VkSemaphore timeline(VkDevice device)
{
    VkSemaphoreTypeCreateInfo type = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                      .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE};
    VkSemaphoreCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &type};
    VkSemaphore s;
    HOST_VK(vkCreateSemaphore(device, &info, NULL, &s));
    return s;
}

int main(int argc, char **argv)
{
    bool trace = false;
    for (int i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "api_qfot_probe: unknown option '%s' (accepted: --validate, --trace-barriers)\n", argv[i]);
            return 2;
        }
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    if (volkInitialize() != VK_SUCCESS) return 1;
    host h;
    host_want_compute_family = true;
    host_create_device(&h, NULL);
    if (h.compute_family == UINT32_MAX) {
        printf("api_qfot_probe: this device has no compute-only queue family (graphics family %u only): no "
               "ownership transfer to record\n", h.family);
        host_destroy_device(&h, NULL);
        return 77;
    }
    host_create_target(&h, 64, 64, VK_FORMAT_R8G8B8A8_UNORM);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    cd.compute_queue = true, cd.compute_queue_family = h.compute_family, cd.compute_queue_index = 0;
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = 64,
                             .height = 64, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "lesson",
                             .bloom = true, .units = VKSKY_UNITS_RELATIVE};
    vksky_renderer *r = NULL;
    if (vksky_renderer_create(c, &d, &r) != VKSKY_SUCCESS) return 1;
    vksky_luts luts;
    if (vksky_get_luts(r, &luts) != VKSKY_SUCCESS) return 1;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 1.0, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(&h, VK_FORMAT_R8G8B8A8_UNORM)};

    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = h.compute_family};
    VkCommandPool pool;
    HOST_VK(vkCreateCommandPool(h.device, &pi, NULL, &pool));
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer lc;
    HOST_VK(vkAllocateCommandBuffers(h.device, &ai, &lc));
    VkSemaphore luts_done = timeline(h.device), frames_done = timeline(h.device);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    if (trace) {
        gpu_barrier_trace(stdout);
        printf("queues graphics=%u:%u compute=%u:0 (another family: exclusive images change owner, release + "
               "acquire)\n", h.family, h.index, h.compute_family);
    }
    int status = 0;
    for (uint64_t frame = 1; frame <= 2; ++frame) {
        /* The rebuild overwrites LUTs the previous frame sampled: it waits for that frame (WAR across queues). */
        bool recorded = false;
        HOST_VK(vkResetCommandBuffer(lc, 0));
        HOST_VK(vkBeginCommandBuffer(lc, &bi));
        gpu_barrier_trace_commands();
        if (vksky_record_luts(r, lc, true, &recorded) != VKSKY_SUCCESS || !recorded) status = 1;
        HOST_VK(vkEndCommandBuffer(lc));
        if (!submit(h.device, h.compute_queue, lc, frames_done, frame - 1, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    luts_done, frame, VK_NULL_HANDLE))
            status = 1;
        host_begin(&h);
        gpu_barrier_trace_commands();
        if (vksky_record(r, h.cmd, &f) != VKSKY_SUCCESS) status = 1;
        host_copy(&h);
        HOST_VK(vkEndCommandBuffer(h.cmd));
        if (!submit(h.device, h.queue, h.cmd, luts_done, frame, luts.ready_stage, frames_done, frame, h.fence)) {
            status = 1;
            continue;
        }
        HOST_VK(vkWaitForFences(h.device, 1, &h.fence, VK_TRUE, UINT64_MAX));
        HOST_VK(vkResetFences(h.device, 1, &h.fence));
    }
    gpu_barrier_trace(NULL);
    vkDeviceWaitIdle(h.device);
    vkDestroySemaphore(h.device, luts_done, NULL);
    vkDestroySemaphore(h.device, frames_done, NULL);
    vkDestroyCommandPool(h.device, pool, NULL);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    if (status) fprintf(stderr, "api_qfot_probe: a vksky call or a submission failed\n");
    if (host_validation_messages) fprintf(stderr, "vksky: validation reported %u messages\n", host_validation_messages);
    return status || host_validation_messages ? 1 : 0;
}
