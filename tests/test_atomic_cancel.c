/* The graceful stop's io half (issue 15 item 3): once the cancel flag handed to io_atomic_set_cancel is set (by the
 * SIGINT/SIGTERM handler in vksky), every writer (PNG, EXR, multilayer EXR) fails with "interrupted", leaves neither
 * the output nor its temporary file, and an existing file at the path is left untouched; with the flag clear the
 * same writes succeed. Deterministic, unlike a signal timed to land inside a write (ctest signals). */
#include "io/atomic_file.h"
#include "io/exr_write.h"
#include "io/png_io.h"
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "check.h"

static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (d) closedir(d);
    return n;
}

static long size_of(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

int main(void)
{
    char dir[] = "/tmp/vksky_cancel_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char png[256], exr[256], old[256], err[512];
    snprintf(png, sizeof png, "%s/a.png", dir);
    snprintf(exr, sizeof exr, "%s/a.exr", dir);
    snprintf(old, sizeof old, "%s/old.png", dir);
    enum { W = 8, H = 4 };
    uint8_t rgba8[W * H * 4];
    uint16_t half[W * H * 4];
    for (int i = 0; i < W * H * 4; ++i) rgba8[i] = (uint8_t)(i * 7), half[i] = 0x3c00;   /* 1.0 */
    io_exr_layer layer = {.name = "", .rgba_half = half};

    static volatile sig_atomic_t stop;
    io_atomic_set_cancel(&stop);
    /* A file that exists before the stop: kept as it is. */
    CHECK(io_write_png(old, W, H, rgba8, 1, err, sizeof err) == 0, "png before the stop: %s", err);
    long old_size = size_of(old);

    stop = 1;
    CHECK(io_write_png(png, W, H, rgba8, 1, err, sizeof err) != 0, "png written after the stop");
    CHECK(strstr(err, "interrupted") != NULL, "png message: %s", err);
    CHECK(io_write_exr(exr, W, H, &layer, 1, err, sizeof err) != 0, "exr written after the stop");
    CHECK(strstr(err, "interrupted") != NULL, "exr message: %s", err);
    CHECK(io_write_png(old, W, H, rgba8, 0, err, sizeof err) != 0, "existing file overwritten after the stop");
    CHECK(size_of(old) == old_size, "the existing file changed");
    CHECK(entries(dir) == 1, "%d entries in %s after the stopped writes (expected only old.png)", entries(dir), dir);

    stop = 0;   /* the flag clear: the same writes succeed */
    CHECK(io_write_png(png, W, H, rgba8, 1, err, sizeof err) == 0, "png: %s", err);
    CHECK(io_write_exr(exr, W, H, &layer, 1, err, sizeof err) == 0, "exr: %s", err);
    CHECK(entries(dir) == 3, "%d entries after the good writes (expected 3)", entries(dir));

    unlink(png), unlink(exr), unlink(old), rmdir(dir);
    if (check_failures) printf("atomic_cancel: %d failure(s)\n", check_failures);
    else printf("atomic_cancel: ok\n");
    return check_failures != 0;
}
