/* vksky image I/O: how images are encoded (issue 27): worker threads for EXR chunks and the EXR compression. Process-
 * wide, set once by the app before any file is written (like the barrier trace and drop controls of gpu/); every
 * writer reads them. The defaults are today's files: ZIP, and as many threads as cores are available. */
#ifndef VKSKY_IO_ENCODE_SETTINGS_H
#define VKSKY_IO_ENCODE_SETTINGS_H

/* The ZIP/ZIPS deflate level when none is asked for: OpenEXR 3.2's default (EXR_DEFAULT_ZLIB_COMPRESS_LEVEL, chosen
 * upstream as the better speed/size trade-off), not 3.1's zlib 6: a 720p sky frame 1.05x the bytes in ~0.6 of the
 * time (docs/performance.md). */
#define IO_EXR_DEFAULT_ZIP_LEVEL 4

typedef struct io_encode_settings {
    int threads;          /* EXR chunk compression (and, issue 28, decoding) threads; 0: the cores available */
    int exr_compression;  /* an exr_compression_t (openexr.h); EXR_COMPRESSION_ZIP by default */
    int zip_level;        /* deflate level 1..9 for ZIP and ZIPS; 0: IO_EXR_DEFAULT_ZIP_LEVEL */
} io_encode_settings;

void io_encode_settings_set(const io_encode_settings *s);
io_encode_settings io_encode_settings_get(void);
/* The thread count in effect for the calling thread: its own share (io_encode_threads_local), else
 * io_encode_threads_all(). */
int io_encode_threads(void);
/* The process's: settings' threads, or the cores available (sched_getaffinity), at least 1. */
int io_encode_threads_all(void);
/* Several files encoded at once (a sequence's frames, app/runs/host_ring.h) share the threads: each encoding
 * thread sets its share here (0: the process's). The bytes do not depend on it: EXR chunks are compressed alone,
 * and a PNG's blocks depend only on whether threads > 1 (png_parallel.h), which a share keeps. */
void io_encode_threads_local(int n);
/* The compression named `name` (zip, zips, piz, rle, none, pxr24, b44, b44a, dwaa, dwab): its exr_compression_t,
 * or -1 for any other name; zip and zips may carry a zlib level, "zip:1" .. "zip:9" (*zip_level; else 0). The
 * inverse, io_exr_compression_name: "?" for an unknown value. */
int io_exr_compression_parse(const char *name, int *zip_level);
const char *io_exr_compression_name(int compression);
/* Whether this OpenEXRCore can write it (3.1 reads DWAA/DWAB but cannot write them). */
int io_exr_compression_writable(int compression);
/* The scanlines in one chunk of a file with this compression (the OpenEXR file layout: none, rle, zips 1; zip, pxr24
 * 16; piz, b44, b44a, dwaa 32; dwab 256), so that a writer in bands can make its bands whole chunks before it opens
 * the file; 1 for an unknown value. */
int io_exr_compression_lines(int compression);
#endif
