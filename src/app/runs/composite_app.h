/* `vksky --composite` and `vksky --render FILE.exr --aovs`: the drivers of the composite pass (issue 12). */
#ifndef VKSKY_APP_COMPOSITE_APP_H
#define VKSKY_APP_COMPOSITE_APP_H
#include "app/cli/options.h"
#include "app/cli/options_composite.h"

/* Exit status: 0, 1 (runtime failure, validation messages), 2 (bad input: one line on stderr, no output file). */
int composite_run(const options *o, const composite_options *co);
/* A plain sky render whose EXR outputs also carry the AOV layers (the composite pass over a frame with no
 * geometry). */
int composite_aovs_run(const options *o, const composite_options *co);
#endif
