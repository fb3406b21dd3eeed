/* vksky image I/O: the process-wide encode settings (encode_settings.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE   /* sched_getaffinity, CPU_COUNT */
#endif
#include "io/encode_settings.h"

#include <openexr.h>
#include <sched.h>
#include <stdbool.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static io_encode_settings settings = {.threads = 0, .exr_compression = EXR_COMPRESSION_ZIP};

void io_encode_settings_set(const io_encode_settings *s) { settings = *s; }
io_encode_settings io_encode_settings_get(void) { return settings; }

/* A thread's own share (io_encode_threads_local): 0, none. */
static _Thread_local int local_threads;

void io_encode_threads_local(int n) { local_threads = n > 0 ? n : 0; }

int io_encode_threads(void)
{
    if (local_threads > 0) return local_threads;
    return io_encode_threads_all();
}

int io_encode_threads_all(void)
{
    if (settings.threads > 0) return settings.threads;
    /* The cores this process may run on (a cpuset or taskset narrows them), not the machine's. */
    cpu_set_t set;
    int n = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : (int)sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? n : 1;
}

static const struct {
    const char *name;
    int value;
} compressions[] = {
    {"none", EXR_COMPRESSION_NONE}, {"rle", EXR_COMPRESSION_RLE},     {"zips", EXR_COMPRESSION_ZIPS},
    {"zip", EXR_COMPRESSION_ZIP},   {"piz", EXR_COMPRESSION_PIZ},     {"pxr24", EXR_COMPRESSION_PXR24},
    {"b44", EXR_COMPRESSION_B44},   {"b44a", EXR_COMPRESSION_B44A},   {"dwaa", EXR_COMPRESSION_DWAA},
    {"dwab", EXR_COMPRESSION_DWAB},
};

int io_exr_compression_parse(const char *name, int *zip_level)
{
    *zip_level = 0;
    if (!name) return -1;
    size_t n = strcspn(name, ":");
    for (size_t i = 0; i < sizeof compressions / sizeof *compressions; ++i) {
        if (strlen(compressions[i].name) != n || strncasecmp(name, compressions[i].name, n)) continue;
        int v = compressions[i].value;
        if (!name[n]) return v;
        bool zlib = v == EXR_COMPRESSION_ZIP || v == EXR_COMPRESSION_ZIPS;
        if (!zlib || name[n + 1] < '1' || name[n + 1] > '9' || name[n + 2]) return -1;
        *zip_level = name[n + 1] - '0';
        return v;
    }
    return -1;
}

const char *io_exr_compression_name(int compression)
{
    for (size_t i = 0; i < sizeof compressions / sizeof *compressions; ++i)
        if (compressions[i].value == compression) return compressions[i].name;
    return "?";
}

int io_exr_compression_lines(int compression)
{
    switch (compression) {
    case EXR_COMPRESSION_ZIP: case EXR_COMPRESSION_PXR24: return 16;
    case EXR_COMPRESSION_PIZ: case EXR_COMPRESSION_B44: case EXR_COMPRESSION_B44A: case EXR_COMPRESSION_DWAA: return 32;
    case EXR_COMPRESSION_DWAB: return 256;
    default: return 1;
    }
}

int io_exr_compression_writable(int compression)
{
    int major = 0, minor = 0, patch = 0;
    exr_get_library_version(&major, &minor, &patch, NULL);
    bool dwa = compression == EXR_COMPRESSION_DWAA || compression == EXR_COMPRESSION_DWAB;
    return !dwa || major > 3 || (major == 3 && minor >= 3);   /* older C libraries: "not yet implemented" */
}
