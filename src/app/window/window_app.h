/* The interactive window's state, shared by window.c (the loop, frames in flight, screenshot, title, setup) and
 * window_input.c (the controls). The swapchain (swapchain.h) knows nothing of it. */
#ifndef VKSKY_APP_WINDOW_APP_H
#define VKSKY_APP_WINDOW_APP_H
#include <volk.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <vksky.h>

#include "app/window/camera.h"
#include "app/cli/options.h"
#include "app/runs/host_async.h"
#include "app/window/swapchain.h"
#include "app/window/window_input.h"

#define FRAMES_IN_FLIGHT 2
#define EXPOSURE_TAU_S 0.5   /* auto exposure's time constant in the window: 63 % of a change of light in 0.5 s */

typedef struct frame_slot {
    VkCommandBuffer cmd;
    VkFence done;              /* signalled when this slot's last submission finished */
    VkSemaphore acquired;
    bool luts_wait;            /* --async-luts: this slot's frame waits for a LUT build on the compute queue */
} frame_slot;

typedef struct stats {
    double start, title_time, last_frame;
    long title_frames;
    double gpu_ms_sum, gpu_ms_total;
    long gpu_samples, gpu_samples_total;
    double steady_time, steady_cpu_ms;   /* wall clock and process CPU at the STEADY_FROM-th presented frame */
} stats;

typedef struct test_hooks {
    bool resize;               /* VKSKY_TEST_RESIZE=1: resize 3 times, minimise and restore once */
    bool report;               /* VKSKY_TEST_REPORT=1: print each swapchain's size and its first present (tests
                                * driving from outside wait for a size to reach the screen before the next) */
    bool present_due;          /* report: a swapchain was created and none of its images presented yet */
    long last_frame;           /* the presented count the hook last acted on */
    int minimized_waits;       /* > 0: we minimised the window; restore after a few idle waits */
    bool hid;                  /* no window manager iconified it: we unmapped it ourselves */
    long f5_frame;             /* VKSKY_TEST_F5=N:FILE: at presented frame N, wait for FILE, then do what F5 does */
    const char *f5_file;
} test_hooks;

typedef struct app {
    const options *o;
    GLFWwindow *window;
    gpu_context ctx;           /* the device, made as the command line makes its own, adopted by `api` */
    vksky_context *api;        /* include/vksky.h: the window records each frame through vksky_record */
    vksky_scene *scene;        /* the command line's scene (F5: vksky_scene_reload) */
    vksky_renderer *renderer;
    host_async async;          /* --async-luts: the LUT passes on the compute queue (app/runs/host_async.h) */
    VkSurfaceKHR surface;
    swapchain sc;
    frame_slot frames[FRAMES_IN_FLIGHT];
    uint32_t slot;
    sky_view view;             /* the frame's values: the camera's, the keys' (tone map, bloom, exposure) */
    camera cam;
    input_state in;
    stats st;
    test_hooks test;
    bool swapchain_dirty;      /* resize seen, or acquire/present reported OUT_OF_DATE / SUBOPTIMAL */
    long presented;
    bool traced;
    int status;
    bool auto_exposure;        /* photometric without --exposure: every frame metered on the GPU (sky/meter.h) */
    double exposure_ease;      /* this frame's share of the way to the metered EV100 (temporal adaptation) */
} app;

/* The window as a host of include/vksky.h (window_api.c). */
/* The context over a->ctx's device, the command line's scene and a renderer of the swapchain's size and format (the
 * bloom chain always allocated, so B can toggle it), the compute queue's host with --async-luts. 0, or the exit
 * status (the line printed). */
int window_api_open(app *a);
/* The renderer, the scene, the async host and the context (the device idle); what was never made is skipped. */
void window_api_close(app *a);
/* One frame into swapchain image `image` of a->sc: a->view's values (view, place, tone map, bloom, exposure or auto
 * exposure), the slot's timer, the capture when asked; ends on the PRESENT barrier. */
void window_api_record(app *a, VkCommandBuffer cmd, uint32_t image, bool capture);
/* --trace-barriers for the calls until the next window_api_trace(a, false): the context's lines on stdout. */
void window_api_trace(app *a, bool on);
/* A call that failed: its line (the message callback printed the details) and exit status 1. */
void window_api_check(vksky_result r, const char *what);
#endif
