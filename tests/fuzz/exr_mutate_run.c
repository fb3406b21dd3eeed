/* exr_mutate_run CORPUS_DIR SECONDS [SEED [CRASH_DIR]]: the EXR reader's fuzzer where clang/libFuzzer is missing
 * (and a second opinion where it is not): loads every file of CORPUS_DIR, then for SECONDS feeds mutants of them to
 * exr_fuzz_one (the libFuzzer harness's body) in memory. Mutations know the format: bit flips, interesting bytes,
 * int32 and uint64 values (sizes, offsets), byte runs deleted, repeated or cut off, two files spliced, and bytes
 * right after a header attribute's name rewritten. A crash signal or a message that is not one line writes the input
 * to CRASH_DIR/exr-crash-SEED-N.exr (add it to tests/exr_regressions/) and exits 1. Prints execs, execs/s. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "exr_fuzz_one.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MAX_FILES 256
#define MAX_LEN (1 << 16)

static uint64_t rng;
static uint64_t next(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return rng;
}
static size_t below(size_t n) { return n ? (size_t)(next() % n) : 0; }

static uint8_t *files[MAX_FILES];
static size_t sizes[MAX_FILES];
static int nfiles;
static uint8_t input[MAX_LEN];
static size_t input_len;
static char crash_path[600];

/* Saves the current input (open/write/close are async-signal-safe: also called from the crash handler). */
static void save_input(void)
{
    int fd = open(crash_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        ssize_t w = write(fd, input, input_len);
        (void)w;
        close(fd);
    }
}

static void on_crash(int sig)
{
    save_input();
    static const char msg[] = "exr_mutate_run: crash, input saved\n";
    ssize_t w = write(2, msg, sizeof msg - 1);
    (void)w;
    signal(sig, SIG_DFL);
    raise(sig);
}

static const char *const attr_names[] = {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                                         "tiles", "chunkCount", "type", "name", "version", "worldToCamera",
                                         "worldToNDC", "chlist", "box2i", "tiledesc", "screenWindowWidth"};
static const int32_t ints[] = {0, 1, -1, 2, 3, 4, 7, 8, 15, 16, 31, 32, 255, 256, 65535, 65536, 65537, 1 << 24,
                               1 << 28, 0x7fffffff, (int32_t)0x80000000, -65536, 16383, 16384};

static void put(size_t at, const void *v, size_t n)
{
    if (at + n <= input_len) memcpy(input + at, v, n);
}

static void mutate(void)
{
    int m = 1 + (int)below(6);
    for (int i = 0; i < m && input_len > 0; ++i) {
        size_t at = below(input_len);
        switch (below(9)) {
        case 0: input[at] ^= (uint8_t)(1u << below(8)); break;
        case 1: input[at] = (uint8_t[]){0, 0xff, 0x7f, 0x80, 1, 2}[below(6)]; break;
        case 2: put(at, &ints[below(sizeof ints / sizeof ints[0])], 4); break;
        case 3: {
            uint64_t v = (uint64_t[]){0, 8, input_len, input_len + 1, ~0ull, 1ull << 40, 0x7fffffffffffffffull}[below(7)];
            put(at, &v, 8);
            break;
        }
        case 4: { /* delete */
            size_t len = 1 + below(32);
            if (at + len > input_len) len = input_len - at;
            memmove(input + at, input + at + len, input_len - at - len);
            input_len -= len;
            break;
        }
        case 5: { /* repeat a run */
            size_t len = 1 + below(64);
            if (at + len > input_len) len = input_len - at;
            if (input_len + len > MAX_LEN) break;
            memmove(input + at + len, input + at, input_len - at);
            input_len += len;
            break;
        }
        case 6: input_len = at; break; /* cut off */
        case 7: { /* splice: our head, another file's tail */
            int f = (int)below((size_t)nfiles);
            size_t from = below(sizes[f]);
            size_t len = sizes[f] - from;
            if (at + len > MAX_LEN) len = MAX_LEN - at;
            memcpy(input + at, files[f] + from, len);
            input_len = at + len;
            break;
        }
        default: { /* rewrite the bytes after an attribute name (its type, size or value) */
            const char *name = attr_names[below(sizeof attr_names / sizeof attr_names[0])];
            size_t nl = strlen(name);
            for (size_t j = 0; j + nl < input_len; ++j) {
                if (memcmp(input + j, name, nl) != 0) continue;
                size_t k = j + nl + 1 + below(24);
                if (below(2))
                    put(k, &ints[below(sizeof ints / sizeof ints[0])], 4);
                else if (k < input_len)
                    input[k] ^= (uint8_t)next();
                break;
            }
        }
        }
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: exr_mutate_run CORPUS_DIR SECONDS [SEED [CRASH_DIR]]\n");
        return 2;
    }
    double seconds = atof(argv[2]);
    uint64_t seed = argc > 3 ? strtoull(argv[3], NULL, 10) : (uint64_t)time(NULL);
    const char *crash_dir = argc > 4 ? argv[4] : ".";
    rng = 0x9E3779B97F4A7C15ull ^ (seed + 1) * 0xBF58476D1CE4E5B9ull;
    DIR *d = opendir(argv[1]);
    if (!d) {
        perror(argv[1]);
        return 2;
    }
    struct dirent *e;
    while ((e = readdir(d)) && nfiles < MAX_FILES) {
        if (e->d_name[0] == '.') continue;
        char p[600];
        snprintf(p, sizeof p, "%s/%s", argv[1], e->d_name);
        FILE *f = fopen(p, "rb");
        if (!f) continue;
        files[nfiles] = (uint8_t *)malloc(MAX_LEN);
        sizes[nfiles] = fread(files[nfiles], 1, MAX_LEN, f);
        fclose(f);
        nfiles++;
    }
    closedir(d);
    if (nfiles == 0) {
        fprintf(stderr, "%s: no corpus files\n", argv[1]);
        return 2;
    }
    signal(SIGSEGV, on_crash), signal(SIGBUS, on_crash), signal(SIGFPE, on_crash), signal(SIGABRT, on_crash),
        signal(SIGILL, on_crash);
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long long execs = 0, refused = 0;
    double elapsed = 0.0;
    int status = 0;
    while (elapsed < seconds) {
        int f = (int)below((size_t)nfiles);
        memcpy(input, files[f], sizes[f]);
        input_len = sizes[f];
        mutate();
        snprintf(crash_path, sizeof crash_path, "%s/exr-crash-%llu-%lld.exr", crash_dir, (unsigned long long)seed,
                 execs);
        int r = exr_fuzz_one(input, input_len);
        ++execs;
        refused += r == 1;
        if (r == 2) {
            save_input();
            fprintf(stderr, "exr_mutate_run: a message that is not one line, input saved as %s\n", crash_path);
            status = 1;
            break;
        }
        if ((execs & 63) == 0) {
            clock_gettime(CLOCK_MONOTONIC, &t);
            elapsed = (double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t);
    elapsed = (double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
    printf("exr_mutate_run: %d corpus files, seed %llu, %lld execs in %.1f s (%.0f execs/s), %lld refused, %s\n",
           nfiles, (unsigned long long)seed, execs, elapsed, (double)execs / (elapsed > 0 ? elapsed : 1), refused,
           status ? "FINDING" : "no findings");
    for (int i = 0; i < nfiles; ++i) free(files[i]);
    return status;
}
