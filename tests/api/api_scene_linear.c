/* VKSKY_OUTPUT_SCENE_LINEAR's error paths through the public API (issue 25): each bad renderer or frame returns its
 * code with one error message on the host's callback, records nothing (the command buffer stays empty: no
 * validation message), and the renderer keeps working afterwards. The pass itself is checked by ctest host_frame
 * (tests/host_frame_probe.c) and, through this API, by ctest example_host (examples/sky_host.c). */
#include "api_host.h"

#define EXPECT(call, code)                                                                                  \
    do {                                                                                                    \
        unsigned errors_ = api_messages[VKSKY_SEVERITY_ERROR];                                              \
        vksky_result got_ = (call);                                                                         \
        HOST_CHECK(got_ == (code), "%s returned %s, expected %s", #call, vksky_result_name(got_), #code);   \
        HOST_CHECK(got_ == VKSKY_SUCCESS || api_messages[VKSKY_SEVERITY_ERROR] == errors_ + 1,              \
                   "%s: %u error messages, expected one", #call, api_messages[VKSKY_SEVERITY_ERROR] - errors_); \
    } while (0)

int main(void)
{
    host h;
    host_create_device(&h, NULL);
    host_create_target(&h, 32, 16, VK_FORMAT_R16G16B16A16_SFLOAT);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    vksky_context *c = NULL;
    vksky_renderer *r = NULL;
    if (vksky_context_create(&cd, &c) != VKSKY_SUCCESS) return 1;

    /* Renderers: the target must be a float storage format. */
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_SCENE_LINEAR, .width = 32,
                             .height = 16, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "low"};
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_UNSUPPORTED);
    d.target_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_SUCCESS);
    if (!r) return 1;

    /* Frames. */
    vksky_camera cam = {.position_m = {0.0, 2.0, 0.0}};
    vksky_camera_look(&cam, 0.0, 10.0, 60.0, 2.0, 0.1);
    vksky_image color = host_image(&h, VK_FORMAT_R16G16B16A16_SFLOAT), not_depth = color;
    vksky_frame f = {.camera = &cam, .color = color};
    host_begin(&h);
    EXPECT(vksky_record(r, h.cmd, &(vksky_frame){.color = color}), VKSKY_ERROR_INVALID_ARGUMENT);   /* no camera */
    vksky_frame bad = f;
    bad.color.extent.width = 31;                                          /* not the renderer's size */
    EXPECT(vksky_record(r, h.cmd, &bad), VKSKY_ERROR_INVALID_ARGUMENT);
    bad = f;
    bad.depth = &not_depth;                                               /* a colour format as the depth */
    EXPECT(vksky_record(r, h.cmd, &bad), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_camera ortho = cam;                                             /* an orthographic projection */
    memset(ortho.projection, 0, sizeof ortho.projection);
    ortho.projection[0] = 0.01, ortho.projection[5] = -0.01, ortho.projection[10] = -0.001, ortho.projection[15] = 1.0;
    bad = f;
    bad.camera = &ortho;
    EXPECT(vksky_record(r, h.cmd, &bad), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_camera below = cam;                                             /* under the ground */
    below.position_m[1] = -10.0;
    vksky_camera_look(&below, 0.0, 10.0, 60.0, 2.0, 0.1);
    bad = f;
    bad.camera = &below;
    EXPECT(vksky_record(r, h.cmd, &bad), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_renderer_resize(r, 32, 16), VKSKY_SUCCESS);
    /* Nothing was recorded: the empty command buffer runs clean. */
    HOST_VK(vkEndCommandBuffer(h.cmd));
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = h.cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci};
    HOST_VK(vkQueueSubmit2(h.queue, 1, &si, h.fence));
    HOST_VK(vkWaitForFences(h.device, 1, &h.fence, VK_TRUE, UINT64_MAX));

    vksky_renderer_destroy(r);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    if (host_failures) fprintf(stderr, "api_scene_linear: %d failure(s)\n", host_failures);
    return host_failures ? 1 : 0;
}
