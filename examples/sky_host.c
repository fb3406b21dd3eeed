/* vksky's example host: an engine's frame with vksky's sky behind its geometry and vksky's aerial perspective on it.
 *
 * The host owns everything: the instance and device (with the features vksky_get_device_requirements asks for),
 * the window and swapchain, its HDR colour image and depth buffer, its mesh (a ground plane and boxes, lit by a
 * Lambert from the sun). Each frame it renders the mesh, then vksky_record (VKSKY_OUTPUT_SCENE_LINEAR) writes the
 * sky where the depth is the far plane and colour x T + S elsewhere, then the host tone-maps to the swapchain.
 *
 *   vksky_example_host [--validate] [--frames N]          a window (N frames, then exit; default: until closed)
 *   vksky_example_host [--validate] --offscreen W H OUT.exr   one frame, no window: the scene-linear image
 *   vksky_example_host [--validate] --offscreen W H OUT.png   the same frame through the window's tone map
 *
 * The boilerplate (device, images, pipelines, swapchain, EXR writer) is in host_vk.c; docs/library.md explains
 * each call below and the contract each image follows. */
#include "host_vk.h"
#include "sky_host_scene.h"
#include <vksky.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh_frag.h"
#include "mesh_vert.h"
#include "tonemap_frag.h"
#include "tonemap_vert.h"

#define HDR_FORMAT VK_FORMAT_R16G16B16A16_SFLOAT
#define DEPTH_FORMAT VK_FORMAT_D32_SFLOAT
typedef struct { float view_proj[16], sun_dir[4], sun_illuminance[4]; } mesh_push;

static void on_vksky(void *user, vksky_severity severity, const char *message)
{
    (void)user;
    fprintf(stderr, "sky_host: vksky %s: %s\n", severity >= VKSKY_SEVERITY_ERROR ? "error" : "message", message);
}

int main(int argc, char **argv)
{
    bool validate = false;
    int frames = -1, width = 960, height = 540;
    const char *out = NULL;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--validate")) validate = true;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--offscreen") && i + 3 < argc)
            width = atoi(argv[i + 1]), height = atoi(argv[i + 2]), out = argv[i + 3], i += 3;
        else {
            fprintf(stderr, "sky_host: unknown or incomplete option '%s' (accepted: --validate, --frames N, "
                            "--offscreen W H OUT.exr|OUT.png)\n", argv[i]);
            return 2;
        }
    }
    size_t out_len = out ? strlen(out) : 0;
    bool png = out_len > 4 && !strcmp(out + out_len - 4, ".png");
    if (width < 1 || height < 1 || width > 8192 || height > 8192 ||
        (out && !png && !(out_len > 4 && !strcmp(out + out_len - 4, ".exr")))) {
        fprintf(stderr, "sky_host: --offscreen W H OUT: W and H in 1..8192, OUT ending in .exr or .png\n");
        return 2;
    }

    /* 1. The host's device, with what vksky needs enabled. */
    GLFWwindow *window = NULL;
    uint32_t ext_count = 0;
    const char **exts = NULL;
    if (!out) {
        if (!glfwInit()) return fprintf(stderr, "sky_host: no display (try --offscreen)\n"), 1;
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        window = glfwCreateWindow(width, height, "vksky example host", NULL, NULL);
        exts = glfwGetRequiredInstanceExtensions(&ext_count);
        if (!window || !exts) return fprintf(stderr, "sky_host: no window\n"), 1;
    }
    vksky_device_requirements req;
    vksky_get_device_requirements(&req);
    VkPhysicalDeviceVulkan13Features f13 = {.synchronization2 = req.synchronization2,
                                            .dynamicRendering = req.dynamic_rendering,
                                            .maintenance4 = req.maintenance4};
    hv_device d;
    hv_device_create(&d, validate, exts, ext_count, window != NULL, &f13);

    /* 2. vksky on the host's device: a context, a scene (Earth, the sun placed), a SCENE_LINEAR renderer. */
    vksky_context *ctx;
    vksky_scene *scene;
    vksky_renderer *sky;
    vksky_context_desc cd = {.abi_version = VKSKY_ABI_VERSION, .get_instance_proc_addr = vkGetInstanceProcAddr,
                             .instance = d.instance, .physical_device = d.gpu, .device = d.device,
                             .queue_family = d.family, .message = on_vksky};
    if (vksky_context_create(&cd, &ctx) || vksky_scene_create_earth(&scene) ||
        vksky_scene_set_sun(scene, SCENE_SUN_AZIMUTH_DEG, SCENE_SUN_ELEVATION_DEG))
        return 1;
    vksky_renderer_desc rd = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_SCENE_LINEAR,
                              .width = (uint32_t)width, .height = (uint32_t)height, .target_format = HDR_FORMAT,
                              .quality = "high", .units = VKSKY_UNITS_RELATIVE, .scene = scene};
    if (vksky_renderer_create(ctx, &rd, &sky)) return 1;
    vksky_luts luts;   /* the sun's illuminance in the units vksky writes: the mesh is lit in the same units */
    vksky_get_luts(sky, &luts);
    vksky_camera cam = {.position_m = {0.0, SCENE_CAMERA_HEIGHT_M, 0.0}, .origin_altitude_m = 0.0};
    vksky_camera_look(&cam, SCENE_YAW_DEG, SCENE_PITCH_DEG, SCENE_FOV_DEG, (double)width / height, SCENE_NEAR_M);

    /* 3. The host's images, mesh and pipeline. */
    VkExtent2D extent = {(uint32_t)width, (uint32_t)height};
    hv_image hdr, depth;
    hv_image_create(&d, &hdr, HDR_FORMAT, extent, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    hv_image_create(&d, &depth, DEPTH_FORMAT, extent, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                    VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    hv_buffer mesh, readback;
    hv_buffer_create(&d, &mesh, (1 + 5 * SCENE_BOX_COUNT) * 6 * 7 * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    hv_buffer_create(&d, &readback, (VkDeviceSize)width * height * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    uint32_t vertices = hv_mesh_build(mesh.mapped);   /* the ground and the boxes of sky_host_scene.h */
    mesh_push push = {.sun_illuminance = {luts.sun_illuminance[0], luts.sun_illuminance[1], luts.sun_illuminance[2]}};
    double az = SCENE_SUN_AZIMUTH_DEG * 3.14159265358979 / 180, el = SCENE_SUN_ELEVATION_DEG * 3.14159265358979 / 180;
    push.sun_dir[0] = (float)(cos(el) * sin(az)), push.sun_dir[1] = (float)sin(el), push.sun_dir[2] = (float)(-cos(el) * cos(az));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += cam.projection[k * 4 + r] * cam.view[c * 4 + k];
            push.view_proj[c * 4 + r] = (float)s;
        }
    VkPushConstantRange pr = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push};
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                      .pushConstantRangeCount = 1, .pPushConstantRanges = &pr};
    VkPipelineLayout layout;
    HV_CHECK(vkCreatePipelineLayout(d.device, &pli, NULL, &layout));
    VkPipeline pipeline = hv_pipeline(&d, layout, spv_mesh_vert, sizeof spv_mesh_vert, spv_mesh_frag,
                                      sizeof spv_mesh_frag, HDR_FORMAT, DEPTH_FORMAT, true);
    hv_window win = {0};
    if (window) hv_window_create(&d, &win, window, hdr.view, spv_tonemap_vert, sizeof spv_tonemap_vert,
                                 spv_tonemap_frag, sizeof spv_tonemap_frag);

    /* 4. Frames: the mesh, vksky, then the tone map (window) or a copy to the host (offscreen). */
    for (int frame = 0; out ? frame < 1 : (frames < 0 || frame < frames) && !glfwWindowShouldClose(window); ++frame) {
        uint32_t index = 0;
        if (window) {
            glfwPollEvents();
            HV_CHECK(vkAcquireNextImageKHR(d.device, win.swapchain, UINT64_MAX, win.acquired, VK_NULL_HANDLE, &index));
        }
        VkCommandBuffer cmd = hv_begin(&d);
        /* The HDR image's last use (the previous frame's tone map or copy) is over: rendered anew, contents dropped. */
        hv_barrier(cmd, hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                   VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        /* The depth buffer: vksky hands it back ready for the depth test (depth.after below); the first frame's
         * starts from nothing. */
        if (frame == 0)
            hv_barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                       VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                       VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                       VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
        VkRenderingAttachmentInfo ca = {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, .imageView = hdr.view,
                                        .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                        .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR, .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
        VkRenderingAttachmentInfo da = ca;
        da.imageView = depth.view, da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;   /* cleared to 0: far */
        VkRenderingInfo ri = {.sType = VK_STRUCTURE_TYPE_RENDERING_INFO, .renderArea = {{0, 0}, extent},
                              .layerCount = 1, .colorAttachmentCount = 1, .pColorAttachments = &ca,
                              .pDepthAttachment = &da};
        vkCmdBeginRendering(cmd, &ri);
        vkCmdSetViewport(cmd, 0, 1, &(VkViewport){0, 0, (float)width, (float)height, 0, 1});
        vkCmdSetScissor(cmd, 0, 1, &(VkRect2D){{0, 0}, extent});
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdPushConstants(cmd, layout, pr.stageFlags, 0, sizeof push, &push);
        vkCmdBindVertexBuffers(cmd, 0, 1, &mesh.buffer, &(VkDeviceSize){0});
        vkCmdDraw(cmd, vertices, 1, 0, 0);
        vkCmdEndRendering(cmd);

        /* vksky: how the host used each image last (before) and how it uses it next (after). */
        vksky_image_use drawn = {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        vksky_image_use next = window ? (vksky_image_use){VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
                                      : (vksky_image_use){VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
        vksky_image_use tested = {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
        vksky_image depth_img = {depth.image, depth.view, DEPTH_FORMAT, extent, tested, tested};
        vksky_frame f = {.camera = &cam, .color = {hdr.image, hdr.view, HDR_FORMAT, extent, drawn, next},
                         .depth = &depth_img};
        if (vksky_record(sky, cmd, &f)) return 1;

        if (out) {   /* offscreen: the copy to a host buffer, submit, wait (host_vk.c) */
            hv_copy_to_host(&d, cmd, hdr.image, extent, &readback);
            continue;
        }
        /* The window: the host's tone map into the swapchain image, submit, present (host_vk.c). */
        hv_window_present(&d, &win, cmd, index);
    }

    /* The file: the scene-linear pixels (EXR), or the window's tone map of them at exposure 1 (PNG). */
    int status = out && (png ? hv_write_png_tonemapped(out, readback.mapped, width, height, 1.0f)
                             : hv_write_exr_half(out, readback.mapped, width, height)) != 0;
    if (status) fprintf(stderr, "sky_host: cannot write %s\n", out);
    vkDeviceWaitIdle(d.device);
    vksky_renderer_destroy(sky);
    vksky_scene_destroy(scene);
    vksky_context_destroy(ctx);
    if (window) hv_window_destroy(&d, &win), glfwDestroyWindow(window), glfwTerminate();
    vkDestroyPipeline(d.device, pipeline, NULL);
    vkDestroyPipelineLayout(d.device, layout, NULL);
    hv_buffer_destroy(&d, &mesh), hv_buffer_destroy(&d, &readback);
    hv_image_destroy(&d, &hdr), hv_image_destroy(&d, &depth);
    hv_device_destroy(&d);
    if (hv_validation_messages()) fprintf(stderr, "sky_host: %u validation message(s)\n", hv_validation_messages());
    return status || hv_validation_messages() ? 1 : status;
}
