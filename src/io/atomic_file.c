/* vksky image I/O: output files appear whole or not at all (a temporary file beside the target, renamed over it
   once complete, removed on failure). See atomic_file.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/atomic_file.h"

#include "io/io_error.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

static const volatile sig_atomic_t *cancel_flag;

void io_atomic_set_cancel(const volatile sig_atomic_t *flag) { cancel_flag = flag; }

/* Splits `path` into a directory (for stat/access: "." when there is no slash) and the length of the
   directory prefix including its trailing slash (0 when there is none). Returns -1 when the basename is
   empty or the path is too long. */
static int split_path(const char *path, char *dir, size_t dir_size, size_t *prefix_len)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        if (dir_size < 2) return -1;
        strcpy(dir, ".");
        *prefix_len = 0;
        return path[0] ? 0 : -1;
    }
    if (slash[1] == '\0') return -1; /* ends with '/': no basename */
    size_t plen = (size_t)(slash - path) + 1;
    size_t dlen = (slash == path) ? 1 : plen - 1; /* "/x" -> dir "/" */
    if (dlen + 1 > dir_size) return -1;
    memcpy(dir, path, dlen);
    dir[dlen] = '\0';
    *prefix_len = plen;
    return 0;
}

/* "<dir>/.<basename>.tmp.<pid>" */
static int make_temp_path(const char *path, char *out, size_t out_size)
{
    char dir[PATH_MAX];
    size_t prefix_len = 0;
    if (split_path(path, dir, sizeof dir, &prefix_len) != 0) return -1;
    int n = snprintf(out, out_size, "%.*s.%s.tmp.%ld", (int)prefix_len, path, path + prefix_len, (long)getpid());
    return (n < 0 || (size_t)n >= out_size) ? -1 : 0;
}

int io_check_writable(const char *path, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        io_set_err(err, err_size, "cannot write '%s': empty path", io_safe_path(path));
        return -1;
    }
    char dir[PATH_MAX];
    size_t prefix_len = 0;
    if (strlen(path) >= PATH_MAX - 32) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(ENAMETOOLONG));
        return -1;
    }
    if (split_path(path, dir, sizeof dir, &prefix_len) != 0) {
        io_set_err(err, err_size, "cannot write '%s': path names a directory, not a file", path);
        return -1;
    }
    struct stat st;
    if (stat(dir, &st) != 0) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(ENOTDIR));
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(EISDIR));
        return -1;
    }
    /* access() says yes to root almost everywhere: probe by creating (and removing) the temp file the writers
       would use. An existing temp file is fine: the writers truncate it. */
    char tmp[PATH_MAX + 64];
    if (make_temp_path(path, tmp, sizeof tmp) != 0) {
        io_set_err(err, err_size, "cannot write '%s': invalid or too long path", path);
        return -1;
    }
    int fd;
    do {
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        if (errno == EEXIST) return 0;
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    close(fd);
    unlink(tmp);
    return 0;
}

/* Opens the temp file for `path`; on failure sets err and returns -1. */
int io_atomic_open(const char *path, char *tmp, size_t tmp_size, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        io_set_err(err, err_size, "cannot write '%s': empty path", io_safe_path(path));
        return -1;
    }
    if (make_temp_path(path, tmp, tmp_size) != 0) {
        io_set_err(err, err_size, "cannot write '%s': invalid or too long path", path);
        return -1;
    }
    int fd;
    do {
        fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    return fd;
}

/* A thread's commit gate (io_atomic_set_commit_gate): NULL, or called before each rename on this thread. */
static _Thread_local io_commit_gate_fn gate_fn;
static _Thread_local void *gate_user;

void io_atomic_set_commit_gate(io_commit_gate_fn fn, void *user) { gate_fn = fn, gate_user = user; }

/* fsync + close `fd` (if >= 0) and rename tmp -> path. On failure unlinks tmp, sets err and returns -1.
   `fd` is always closed. */
static int commit(int fd, const char *tmp, const char *path, char *err, size_t err_size)
{
    /* A stop asked for while the file was written: whole or not at all, so not at all. */
    if (cancel_flag && *cancel_flag) {
        io_atomic_abort(fd, tmp);
        io_set_err(err, err_size, "cannot write '%s': interrupted", path);
        return -1;
    }
    if (fd >= 0) {
        if (fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
            int e = errno;
            close(fd);
            unlink(tmp);
            io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(e));
            return -1;
        }
        if (close(fd) != 0) {
            int e = errno;
            unlink(tmp);
            io_set_err(err, err_size, "cannot write '%s': %s", path, strerror(e));
            return -1;
        }
    }
    /* Files written at once (a sequence's frames on several encoders) are renamed in the caller's order: the gate
     * waits for this file's turn (the fsync above ran in parallel). A stop that came meanwhile drops this one. */
    if (gate_fn) {
        gate_fn(gate_user);
        if (cancel_flag && *cancel_flag) {
            unlink(tmp);
            io_set_err(err, err_size, "cannot write '%s': interrupted", path);
            return -1;
        }
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        io_set_err(err, err_size, "cannot write '%s': rename from temp file failed: %s", path, strerror(e));
        return -1;
    }
    return 0;
}

/* Wall time spent committing files so far (--timings: "write" apart from encoding). */
static _Atomic long long commit_us;   /* several encoders may commit at once */

double io_atomic_commit_ms(void) { return (double)commit_us * 1e-3; }

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

int io_atomic_commit(int fd, const char *tmp, const char *path, char *err, size_t err_size)
{
    double start = now_ms();
    int rc = commit(fd, tmp, path, err, err_size);
    commit_us += (long long)((now_ms() - start) * 1e3);
    return rc;
}

void io_atomic_abort(int fd, const char *tmp)
{
    if (fd >= 0) close(fd);
    unlink(tmp);
}
