/* vksky image I/O: the error convention every reader and writer of this module follows. Functions never crash on
 * bad arguments: they return -1 and write a one-line reason (no trailing newline) into err[err_size] (err may be
 * NULL or err_size 0, in which case the message is dropped). Internal to src/io/.
 */
#ifndef VKSKY_IO_IO_ERROR_H
#define VKSKY_IO_IO_ERROR_H

#include <stddef.h>

/* Largest image we accept in either direction (also keeps every size computation far from overflow). */
#define IO_MAX_DIM (1 << 16)

/* printf-style message into err[err_size], folded onto one line without trailing blanks. */
void io_set_err(char *err, size_t err_size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* `path`, or "(null)" for messages about a NULL path. */
const char *io_safe_path(const char *path);

/* Opens `path` for reading just to produce an errno-based message before handing it to a library: 0 when it is a
   readable regular file, else -1 + "cannot read '<path>': <reason>". */
int io_check_readable(const char *path, char *err, size_t err_size);

/* The arguments every writer checks first: a non-empty path and a size in [1, IO_MAX_DIM]^2. 0, or -1 + err. */
int io_check_image_target(const char *path, int width, int height, char *err, size_t err_size);

#endif /* VKSKY_IO_IO_ERROR_H */
