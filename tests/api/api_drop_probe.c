/* The library's barriers on the host's image, proven like the CLI's (tests/barrier_drops.txt, config api): a host
 * with its own device records two DISPLAY frames into one command buffer, each followed by its own copy of the image
 * (the image's `after` use), under validation + synchronization validation. Run by tests/barrier_drop_test.sh in
 * vksky's place: `--validate` and `--trace-barriers` are its options, VKSKY_DROP_BARRIER / VKSKY_WEAKEN_BARRIER name
 * the barrier to change, messages are printed as vksky prints them and any makes the exit status 1.
 * Built from libvksky's objects (not the .so) to reach the trace and drop switches; the host's Vulkan calls go
 * through volk's table, the one the library fills from the host's vkGetInstanceProcAddr. */
#include <volk.h>
#include "api_host.h"
#include "gpu/barrier.h"

int main(int argc, char **argv)
{
    bool trace = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "api_drop_probe: unknown option '%s' (accepted: --validate, --trace-barriers)\n", argv[i]);
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
    host_create_target(&h, 64, 64, VK_FORMAT_R8G8B8A8_UNORM);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    vksky_context *c = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = 64,
                             .height = 64, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "lesson",
                             .bloom = true, .units = VKSKY_UNITS_RELATIVE};
    vksky_renderer *r = NULL;
    if (vksky_renderer_create(c, &d, &r) != VKSKY_SUCCESS) return 1;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 1.0, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(&h, VK_FORMAT_R8G8B8A8_UNORM)};
    if (trace) gpu_barrier_trace(stdout);
    host_begin(&h);
    for (int frame = 0; frame < 2; ++frame) {
        if (frame > 0) {
            /* The host's own: its two copies write one buffer (WAW). */
            VkBufferMemoryBarrier2 waw = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                                          .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                          .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                          .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                          .dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                          .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                          .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .buffer = h.buffer,
                                          .size = VK_WHOLE_SIZE};
            VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1,
                                    .pBufferMemoryBarriers = &waw};
            vkCmdPipelineBarrier2(h.cmd, &dep);
        }
        if (vksky_record(r, h.cmd, &f) != VKSKY_SUCCESS) return 1;
        if (frame == 0) {
            gpu_barrier_trace_pass("host copy");   /* the host's own pass between the frames, for the trace */
            host_copy(&h);
        }
    }
    host_end_and_read(&h);
    gpu_barrier_trace(NULL);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    if (host_validation_messages) fprintf(stderr, "vksky: validation reported %u messages\n", host_validation_messages);
    return host_validation_messages ? 1 : 0;
}
