/* vksky image I/O: what the OpenEXR writer and reader share: the library's error messages, captured per thread,
   and the channel names of a layer. See exr_common.h. */
#include "io/exr_common.h"

#include <stdio.h>

/* The OpenEXRCore error callback delivers messages on the failing thread; keep the last one per thread
   instead of letting the library print to stderr. */
static _Thread_local char g_exr_msg[512];

void io_exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(g_exr_msg, sizeof g_exr_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

const char *io_exr_msg(exr_result_t rc)
{
    if (g_exr_msg[0]) return g_exr_msg;
    return exr_get_default_error_message(rc);
}

void io_exr_clear_msg(void) { g_exr_msg[0] = '\0'; }

/* Channel name for layer `name` and component index c (0..3 = R,G,B,A). */
void io_exr_channel_name(char *out, size_t out_size, const char *layer, int c)
{
    static const char comp[4] = {'R', 'G', 'B', 'A'};
    if (layer[0])
        snprintf(out, out_size, "%s.%c", layer, comp[c]);
    else
        snprintf(out, out_size, "%c", comp[c]);
}
