/* libFuzzer harness for the command line (issue 15 item 4): the input is split at newlines into arguments (at most
 * 32, each at most 200 bytes; a NUL ends an argument early) and parsed as main parses before it renders anything:
 * composite_options_extract takes the composite's flags out, then options_parse. The properties (app_fuzz_common.h):
 * status 0 or 2; one "vksky: " line on 2; on 0 a silent parse whose dump round-trips.
 * Two arguments are tamed so that a run stays in the process and on the parser: --dump-scene (prints and exits) is
 * dropped, and a --scene value is replaced by one of the shipped scenes (chosen by the value's bytes), since a path
 * from the fuzzer could name /dev/stdin or a FIFO; the scene's bytes are fuzz_scene's job. Seed corpus: command
 * lines from the tests and the README (tests/fuzz/cli_corpus, one argument per line). */
#include "app_fuzz_common.h"
#include "app/cli/options_composite.h"

#ifndef VKSKY_FUZZ_SCENES
#error "VKSKY_FUZZ_SCENES: the shipped scenes' directory"
#endif

enum { MAX_ARGS = 32, MAX_ARG = 200 };

static const char *const shipped[] = {"earth-clear", "earth-hazy", "mars", "earth-boundary-layer", "lesson-single-scatter"};

/* A shipped scene's path for a fuzzed --scene value (one that exists: those without a file fall back to the first). */
static const char *scene_for(const char *value)
{
    static char path[4096];
    unsigned h = 0;
    for (const char *p = value; *p; ++p) h = h * 31u + (unsigned char)*p;
    for (size_t k = 0; k < sizeof shipped / sizeof shipped[0]; ++k) {
        snprintf(path, sizeof path, "%s/%s.json", VKSKY_FUZZ_SCENES,
                 shipped[(h + k) % (sizeof shipped / sizeof shipped[0])]);
        if (access(path, R_OK) == 0) return path;
    }
    return path;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char store[MAX_ARGS][MAX_ARG + 1];
    static char scene_arg[4200];
    char *argv[MAX_ARGS + 2] = {"vksky"};
    int argc = 1;
    size_t at = 0;
    while (at < size && argc <= MAX_ARGS) {
        size_t end = at;
        while (end < size && data[end] != '\n') ++end;
        size_t n = end - at < MAX_ARG ? end - at : MAX_ARG;
        char *arg = store[argc - 1];
        memcpy(arg, data + at, n);
        arg[n] = '\0';   /* an embedded NUL ends the argument early, as in a real argv */
        at = end + 1;
        if (!strncmp(arg, "--dump-scene", 12)) continue;
        if (!strncmp(arg, "--scene=", 8)) {
            snprintf(scene_arg, sizeof scene_arg, "--scene=%s", scene_for(arg + 8));
            argv[argc++] = scene_arg;
            continue;
        }
        if (argc >= 2 && !strcmp(argv[argc - 1], "--scene")) {
            argv[argc++] = (char *)scene_for(arg);
            continue;
        }
        argv[argc++] = arg;
    }
    argv[argc] = NULL;
    /* As main: the composite's flags leave argv first (their own parser), then the shared table's parse. */
    composite_options co;
    char *err = NULL;
    size_t n = 0;
    FILE *saved = stderr, *mem = open_memstream(&err, &n);
    if (!mem) fuzz_fail("open_memstream", NULL);
    stderr = mem;
    int rc = composite_options_extract(&co, &argc, argv);
    stderr = saved;
    fclose(mem);
    if (rc == 2) {
        char *nl = strchr(err, '\n');
        if (strncmp(err, "vksky: ", 7) != 0 || !nl || nl[1] != '\0')
            fuzz_fail("composite flags: status 2 without exactly one 'vksky: ' line on stderr", err);
    } else if (rc != 0 || err[0]) {
        fuzz_fail("composite flags: a status other than 0 or 2, or a message with 0", err);
    } else {
        fuzz_check_command_line(argc, argv);
    }
    free(err);
    return 0;
}
