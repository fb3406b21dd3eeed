/* vksky image I/O: the one-line error messages every reader and writer returns, and the readability check that
   turns a missing or odd input file into such a message before a library sees it. See io_error.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/io_error.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void io_set_err(char *err, size_t err_size, const char *fmt, ...)
{
    if (!err || err_size == 0) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
    if (n < 0) {
        err[0] = '\0';
        return;
    }
    /* One line, no trailing newline. */
    for (char *p = err; *p; ++p) {
        if (*p == '\n' || *p == '\r') *p = ' ';
    }
    size_t len = strlen(err);
    while (len > 0 && err[len - 1] == ' ') err[--len] = '\0';
}

const char *io_safe_path(const char *path) { return path ? path : "(null)"; }

/* Opens `path` for reading just to produce an errno-based message before handing it to a library. */
int io_check_readable(const char *path, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        io_set_err(err, err_size, "cannot read '%s': empty path", io_safe_path(path));
        return -1;
    }
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        io_set_err(err, err_size, "cannot read '%s': %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    int ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    close(fd);
    if (!ok) {
        io_set_err(err, err_size, "cannot read '%s': not a regular file", path);
        return -1;
    }
    return 0;
}

int io_check_image_target(const char *path, int width, int height, char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (!path || !path[0]) {
        io_set_err(err, err_size, "cannot write '%s': empty path", p);
        return -1;
    }
    if (width <= 0 || height <= 0 || width > IO_MAX_DIM || height > IO_MAX_DIM) {
        io_set_err(err, err_size, "cannot write '%s': invalid image size %dx%d", p, width, height);
        return -1;
    }
    return 0;
}
