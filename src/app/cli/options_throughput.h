/* --threads and --exr-compression (issue 27): how files are encoded, never what the image is. */
#ifndef VKSKY_APP_OPTIONS_THROUGHPUT_H
#define VKSKY_APP_OPTIONS_THROUGHPUT_H
#include "app/cli/options_struct.h"

/* One of this file's flags: 0, or 2 with the message printed; -1: not one of them. */
int options_throughput_apply(options *o, const char *flag_name, const char *value, double x);
/* The options' encode settings handed to io/ (process-wide: io/encode_settings.h). */
void options_throughput_install(const options *o);
#endif
