#include "app/window.h"

int window_run(const options *o)
{
    (void)o;
    fprintf(stderr, "vksky: nothing to do; give --render FILE.exr|FILE.png or --bench N (see --help)\n");
    return 2;
}
