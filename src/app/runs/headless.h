/* Headless driver: render one frame to files, or benchmark. */
#ifndef VKSKY_APP_HEADLESS_H
#define VKSKY_APP_HEADLESS_H
#include "app/cli/options.h"

/* Exit status: 0 ok, 1 runtime failure (or validation messages), 2 bad input. */
int headless_run(const options *o);
#endif
