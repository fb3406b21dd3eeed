/* The window as a host of include/vksky.h (window_app.h): the device the window made, adopted by a vksky context as
 * the command line's headless run adopts its own (app/runs/headless.c); the command line's scene as a value
 * (vksky_scene_from_args; F5 reloads it: window_input.c); each frame one vksky_record into the slot's command buffer
 * and the acquired swapchain image, the frame's values as extension structs (ABI 3): the fly camera's view and place,
 * the keys' tone map, bloom and exposure, the slot's timer and auto exposure, the screenshot's capture, and the image's
 * uses as a swapchain's, so its barriers keep the window's names (display.to_attachment, display.to_present). No
 * src/sky or src/lib header (tests/layering_test.sh). */
#include "app/window/window_app.h"
#include "app/runs/host_device.h"
#include "app/runs/host_print.h"
#include <stdlib.h>

void window_api_check(vksky_result r, const char *what)
{
    if (r == VKSKY_SUCCESS) return;
    fprintf(stderr, "vksky: %s failed: %s\n", what, vksky_result_name(r));
    exit(1);
}

int window_api_open(app *a)
{
    const options *o = a->o;
    const gpu_context *g = &a->ctx;
    if (host_device_adopt(g, &a->api) != 0) return 1;
    /* The scene, view settings and quality of the command line the window was started with (the same parser). */
    if (vksky_scene_from_args(o->argc, o->argv, host_print_message, NULL, &a->scene) != VKSKY_SUCCESS) return 1;
    /* The bloom chain is always allocated so B can toggle it; --no-bloom only starts with it off (a->view.bloom). */
    vksky_renderer_desc rd = {
        .abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = a->sc.extent.width,
        .height = a->sc.extent.height, .target_format = a->sc.format.format, .quality = "scene", .bloom = true,
        .units = o->units == OPTIONS_UNITS_RELATIVE ? VKSKY_UNITS_RELATIVE : VKSKY_UNITS_PHOTOMETRIC, .scene = a->scene};
    if (vksky_renderer_create(a->api, &rd, &a->renderer) != VKSKY_SUCCESS) return 1;
    if (g->compute_queue && host_async_create(&a->async, a->api, g->compute_index, NULL)) return 1;
    return 0;
}

void window_api_close(app *a)
{
    vksky_renderer_destroy(a->renderer);
    host_async_destroy(&a->async);
    vksky_scene_destroy(a->scene);
    vksky_context_destroy(a->api);
    a->renderer = NULL, a->scene = NULL, a->api = NULL;
}

void window_api_trace(app *a, bool on)
{
    /* The screenshot's frame traced after the first (VKSKY_TRACE_CAPTURE=1): a command buffer of its own. */
    if (on && a->traced) host_print_trace(NULL, "commands");
    vksky_context_set_trace(a->api, on ? VKSKY_TRACE_BARRIERS : 0u, on ? host_print_trace : NULL, NULL);
    if (a->async.device) a->async.trace = on ? stdout : NULL;   /* its LUT submission's semaphore lines */
}

void window_api_record(app *a, VkCommandBuffer cmd, uint32_t image, bool capture)
{
    const sky_view *v = &a->view;
    vksky_frame_timer timer = {.type = VKSKY_STRUCTURE_TYPE_FRAME_TIMER, .slot = a->slot};
    vksky_frame_swapchain swapchain = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN, .next = &timer};
    vksky_frame_capture shot = {.type = VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE, .next = &swapchain};
    vksky_frame_display display = {.type = VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY,
                                   .next = capture ? (const void *)&shot : (const void *)&swapchain,
                                   .tonemap = (vksky_tonemap)v->tonemap, .bloom = v->bloom};
    /* The fly camera's altitude and sun as the same doubles its view holds (no matrices: the same rays). */
    vksky_frame_place place = {.type = VKSKY_STRUCTURE_TYPE_FRAME_PLACE, .next = &display,
                               .altitude_km = v->altitude_km, .sun_azimuth_deg = v->sun_azimuth_deg,
                               .sun_elevation_deg = v->sun_elevation_deg};
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .next = &place, .yaw_deg = v->yaw_deg,
                             .pitch_deg = v->pitch_deg, .fov_deg = v->fov_deg};
    /* Auto exposure: the GPU meters this frame and its tone map reads the result (slot: the frame slot's). */
    vksky_auto_exposure metered = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, .next = &view, .slot = a->slot,
                                   .ease = a->exposure_ease};
    vksky_frame f = {.next = a->auto_exposure ? (const void *)&metered : (const void *)&view,
                     .exposure = v->exposure_ev,
                     .color = {.image = a->sc.images[image], .view = a->sc.views[image], .format = a->sc.format.format,
                               .extent = a->sc.extent}};
    window_api_check(vksky_record(a->renderer, cmd, &f), "vksky_record");
}
