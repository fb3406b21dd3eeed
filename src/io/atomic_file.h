/* vksky image I/O: atomic output files. A writer opens "<dir>/.<basename>.tmp.<pid>", writes it, and rename()s it
 * over `path` only once everything succeeded; on failure the temp file is removed and `path` is left untouched
 * (no new file is created; an existing one is kept). Errors follow io_error.h.
 */
#ifndef VKSKY_IO_ATOMIC_FILE_H
#define VKSKY_IO_ATOMIC_FILE_H

#include <signal.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Checks that `path` can be created before expensive work: the directory exists and is writable (verified by
   creating and removing the writers' temp file, since access() always says yes to root). 0 ok, -1 + err. */
int io_check_writable(const char *path, char *err, size_t err_size);

/* Opens (creates or truncates) the temp file for `path`, its name into tmp[tmp_size]; returns the fd, or -1 + err. */
int io_atomic_open(const char *path, char *tmp, size_t tmp_size, char *err, size_t err_size);

/* fsync + close `fd` (if >= 0) and rename tmp -> path. On failure unlinks tmp and returns -1 + err. `fd` is always
   closed. */
int io_atomic_commit(int fd, const char *tmp, const char *path, char *err, size_t err_size);

/* Milliseconds (wall) this process spent in io_atomic_commit so far: the fsync, close and rename of its files. */
double io_atomic_commit_ms(void);

/* Gives up: closes `fd` (if >= 0) and removes the temp file. */
void io_atomic_abort(int fd, const char *tmp);

/* A flag (set by a signal handler: the graceful stop) that, once nonzero, makes io_atomic_commit abandon the file it
   is about to rename into place: removes the temp file and fails with "interrupted". NULL (the default): never. */
void io_atomic_set_cancel(const volatile sig_atomic_t *flag);

/* A commit gate for this thread (NULL: none): io_atomic_commit calls fn(user) after the fsync and before the rename,
   so that files encoded at once on several threads still appear in one order (a sequence's frames: a stop leaves
   the first frames, never a gap); a stop that arrives while it waits abandons the file. */
typedef void (*io_commit_gate_fn)(void *user);
void io_atomic_set_commit_gate(io_commit_gate_fn fn, void *user);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_ATOMIC_FILE_H */
