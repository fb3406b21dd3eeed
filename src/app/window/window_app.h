/* The interactive window's state, shared by window.c (the loop, frames in flight, screenshot, title, setup) and
 * window_input.c (the controls). The swapchain (swapchain.h) knows nothing of it. */
#ifndef VKSKY_APP_WINDOW_APP_H
#define VKSKY_APP_WINDOW_APP_H
#include <volk.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/window/camera.h"
#include "app/cli/options.h"
#include "app/window/swapchain.h"
#include "app/window/window_input.h"

#define FRAMES_IN_FLIGHT 2
#define EXPOSURE_TAU_S 0.5   /* auto exposure's time constant in the window: 63 % of a change of light in 0.5 s */

typedef struct frame_slot {
    VkCommandBuffer cmd;
    VkFence done;              /* signalled when this slot's last submission finished */
    VkSemaphore acquired;
    gpu_timer timer;
    bool timer_unread;         /* submitted; its timestamps are not yet read */
    VkCommandBuffer luts;      /* --async-luts: the LUT passes this slot's frame waited for (compute pool) */
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
    bool report;               /* VKSKY_TEST_REPORT=1: print each swapchain's size (tests driving from outside) */
    long last_frame;           /* the presented count the hook last acted on */
    int minimized_waits;       /* > 0: we minimised the window; restore after a few idle waits */
    bool hid;                  /* no window manager iconified it: we unmapped it ourselves */
    long f5_frame;             /* VKSKY_TEST_F5=N:FILE: at presented frame N, wait for FILE, then do what F5 does */
    const char *f5_file;
} test_hooks;

typedef struct app {
    const options *o;
    GLFWwindow *window;
    gpu_context ctx;
    VkSurfaceKHR surface;
    swapchain sc;
    frame_slot frames[FRAMES_IN_FLIGHT];
    uint32_t slot;
    sky_renderer renderer;
    sky_view view;
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
#endif
