/* vksky image I/O: what the OpenEXR writer and reader share. Internal to src/io/. */
#ifndef VKSKY_IO_EXR_COMMON_H
#define VKSKY_IO_EXR_COMMON_H

#include <stddef.h>

#include <openexr.h>

/* Longest layer name accepted (channel names are "<layer>.R" etc.). */
#define IO_EXR_MAX_LAYER_NAME 200

/* The OpenEXRCore error callback delivers messages on the failing thread; keep the last one per thread instead of
   letting the library print to stderr. Install io_exr_error_handler in the context initializer, clear the message
   before a call sequence, and read it back with io_exr_msg (the library's default text when none was captured). */
void io_exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg);
void io_exr_clear_msg(void);
const char *io_exr_msg(exr_result_t rc);

/* Channel name for layer `layer` ("" = the default layer) and component index c (0..3 = R,G,B,A). */
void io_exr_channel_name(char *out, size_t out_size, const char *layer, int c);

#endif /* VKSKY_IO_EXR_COMMON_H */
