/* Shared by the command-line and scene-loader libFuzzer harnesses (fuzz_cli.c, fuzz_scene.c; issue 15 item 4): the
 * properties every input must keep, checked in the process, and the plumbing to check them.
 *  - options_parse returns 0 or 2 and nothing else (a crash, a sanitizer report or a hang is libFuzzer's finding);
 *  - on 2: exactly one line on stderr, starting "vksky: ";
 *  - on 0: nothing on stderr, and the scene --dump-scene would print loads back (status 0) to the very same dump.
 * A broken property aborts, so libFuzzer keeps the input as a finding like any crash. stderr is captured by pointing
 * glibc's `stderr` at a memory stream for the call (harness only: C says no more than that stderr is an expression). */
#ifndef VKSKY_TESTS_FUZZ_APP_FUZZ_COMMON_H
#define VKSKY_TESTS_FUZZ_APP_FUZZ_COMMON_H
#define _GNU_SOURCE
#include "app/cli/options.h"
#include "app/scene/scene_dump.h"
#include "gpu/context.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* --quality auto asks the Vulkan loader which kind of device there is (gpu_device_type), and lavapipe brings in
 * LLVM, which stays loaded (nodelete) and whose C++ translation units construct the standard streams on first load,
 * bound to whatever `stderr` is at that moment: inside a parse, the capture's memory stream, closed right after; at
 * exit the C++ runtime flushes it (a SEGV in std::ios_base::Init's destructor). So the harness asks once before any
 * capture: the driver loads with the real stderr, and the answer is cached for the process. */
__attribute__((constructor)) static void fuzz_probe_device_first(void)
{
    VkPhysicalDeviceType type;
    (void)gpu_device_type(-1, &type);
}

static void fuzz_fail(const char *what, const char *detail)
{
    fprintf(stderr, "fuzz property broken: %s\n%s\n", what, detail ? detail : "");
    abort();
}

/* A file in memory (memfd) holding `text`, reachable by path: "/proc/self/fd/N" (the loader opens paths). One per
 * slot, made once, rewritten for every input. */
static const char *fuzz_memfile(int slot, const char *text, size_t len)
{
    static int fd[2] = {-1, -1};
    static char path[2][64];
    if (fd[slot] < 0) {
        fd[slot] = memfd_create("vksky-fuzz", 0);
        if (fd[slot] < 0) fuzz_fail("memfd_create", NULL);
        snprintf(path[slot], sizeof path[slot], "/proc/self/fd/%d", fd[slot]);
    }
    if (ftruncate(fd[slot], 0) != 0 || pwrite(fd[slot], text, len, 0) != (ssize_t)len) fuzz_fail("memfd write", NULL);
    return path[slot];
}

/* options_parse with stderr captured: the status, and what it printed (malloc'd, NUL-terminated) in *err. */
static int fuzz_parse(options *o, int argc, char **argv, char **err)
{
    size_t n = 0;
    FILE *saved = stderr, *mem = open_memstream(err, &n);
    if (!mem) fuzz_fail("open_memstream", NULL);
    stderr = mem;
    int rc = options_parse(o, argc, argv);
    stderr = saved;
    fclose(mem);
    return rc;
}

/* The scene --dump-scene would print for *o (malloc'd). */
static char *fuzz_dump(const options *o)
{
    char *text = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&text, &n);
    if (!mem) fuzz_fail("open_memstream", NULL);
    if (scene_dump(o, mem) != 0) fuzz_fail("scene_dump failed", NULL);
    fclose(mem);
    return text;
}

/* The properties above for one command line (argv[0] is the program's name; --dump-scene is left out: the parse
 * returns, but its projection note on stderr would read as a finding). */
static void fuzz_check_command_line(int argc, char **argv)
{
    options o;
    char *err = NULL;
    int rc = fuzz_parse(&o, argc, argv, &err);
    if (rc == 2) {
        char *nl = strchr(err, '\n');
        if (strncmp(err, "vksky: ", 7) != 0 || !nl || nl[1] != '\0')
            fuzz_fail("status 2 without exactly one 'vksky: ' line on stderr", err);
    } else if (rc == 0) {
        if (err[0]) fuzz_fail("status 0 with output on stderr", err);
        /* Accepted: its dump loads back to the same dump (what `vksky --scene DUMP --dump-scene` does). */
        char *d1 = fuzz_dump(&o);
        char *argv2[] = {"vksky", "--scene", (char *)fuzz_memfile(1, d1, strlen(d1)), NULL};
        options o2;
        char *err2 = NULL;
        if (fuzz_parse(&o2, 3, argv2, &err2) != 0) fuzz_fail("the dump of an accepted input does not load", err2);
        char *d2 = fuzz_dump(&o2);
        if (strcmp(d1, d2) != 0) fuzz_fail("an accepted input's dump does not round-trip", d1);
        free(err2);
        free(d1);
        free(d2);
        options_release(&o2);
        options_release(&o);   /* a sequence's parse keeps its unresolved options (options_frame) */
    } else {
        char status[64];
        snprintf(status, sizeof status, "options_parse returned %d (expected 0 or 2)", rc);
        fuzz_fail(status, err);
    }
    free(err);
}
#endif
