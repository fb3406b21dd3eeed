/* Interactive window: GLFW + Vulkan swapchain presentation, fly camera, the lesson's controls. */
#ifndef VKSKY_APP_WINDOW_H
#define VKSKY_APP_WINDOW_H
#include "app/cli/options.h"

/* Exit status: 0 ok, 1 runtime failure (or validation messages), 2 bad input / no display. */
int window_run(const options *o);
#endif
