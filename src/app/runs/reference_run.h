/* --reference: the CPU ground truth (the converged model, or the path tracer) from the command line. */
#ifndef VKSKY_APP_REFERENCE_RUN_H
#define VKSKY_APP_REFERENCE_RUN_H
#include "app/cli/options.h"

/* Prints "R G B" along the view axis, or with --render FILE.exr writes a reference image. Exit status as
 * headless_run. */
int reference_run(const options *o);
#endif
