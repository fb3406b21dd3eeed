/* vksky_scene_set_values and a scene's loads on one thread take no other thread's stderr or stdout line (the encode_frames flake: the command
 * line's readback ring prints a frame's progress line on a consumer thread while the producer sets the next frame's
 * values; the library pointed the process's stderr at its capture meanwhile, and the line went into the capture).
 * One thread sets a sequence's values over and over, another prints numbered lines to stderr, a file of this test's:
 * every line is there, once, in order, and nothing else (the library prints nothing of its own). The capture still
 * serves its own thread: a frame whose values the command line refuses gets that one line on its callback, on the
 * setting thread, and none on stderr. A second thread loads scenes over and over: a file that does not exist (its one
 * line captured for the callback) and a command line with --max-error (whose pick the command line prints on stdout;
 * the library drops it): neither takes a line of the main thread's stderr or stdout, which it prints meanwhile (the
 * loads pointed the process's streams at their captures before). No GPU. */
#include "api_host.h"
#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>

enum { LINES = 20000 };

static char *seq_argv[] = {"vksky", "--width", "16", "--height", "16", "--quality", "low", "--date", "2024-06-21",
                           "--latitude", "45", "--longitude", "5", "--frame-count", "7", "--animate", "time=6:18",
                           "--animate", "latitude=40:50", "--render", "unused_%d.png"};

typedef struct setter {
    vksky_scene *scene;
    atomic_bool stop;
    long sets, failures;
} setter;

static void *set_values_loop(void *arg)
{
    setter *s = arg;
    const char *flags[2] = {"--time", "--latitude"};
    for (long i = 0; !atomic_load(&s->stop); ++i) {
        double v[2] = {6.0 + (double)(i % 7) * 2.0, 40.0 + (double)(i % 7)};
        s->failures += vksky_scene_set_values(s->scene, 2, flags, v, api_message, NULL) != VKSKY_SUCCESS;
        ++s->sets;
    }
    return NULL;
}

/* A loader: a scene file that does not exist (refused, its line on the callback) and a command line whose --max-error
 * pick the command line would print on stdout, in turn. */
typedef struct loader {
    atomic_bool stop;
    long loads, unexpected;
} loader;

static void quiet_message(void *user, vksky_severity severity, const char *text) { (void)user, (void)severity, (void)text; }

static void *load_loop(void *arg)
{
    loader *l = arg;
    static char *pick_argv[] = {"vksky", "--width", "16", "--height", "16", "--max-error", "0.02",
                                "--render", "unused.exr"};
    for (long i = 0; !atomic_load(&l->stop); ++i) {
        vksky_scene *scene = NULL;
        vksky_result r = i % 2 ? vksky_scene_load("/nonexistent/api_values_threads.json", quiet_message, NULL, &scene)
                               : vksky_scene_from_args((int)(sizeof pick_argv / sizeof *pick_argv), pick_argv,
                                                       quiet_message, NULL, &scene);
        l->unexpected += (i % 2) ? r == VKSKY_SUCCESS : r != VKSKY_SUCCESS;
        vksky_scene_destroy(scene);
        ++l->loads;
    }
    return NULL;
}

/* The refused frame's line: its text, and the thread it came on. */
static char refused_text[512];
static pthread_t refused_thread;
static int refused_count;
static void refused_message(void *user, vksky_severity severity, const char *text)
{
    (void)user, (void)severity;
    snprintf(refused_text, sizeof refused_text, "%s", text);
    refused_thread = pthread_self();
    ++refused_count;
}

int main(void)
{
    vksky_scene *scene = host_scene_of_args((int)(sizeof seq_argv / sizeof *seq_argv), seq_argv);
    char path[] = "/tmp/api_values_threads_XXXXXX";
    int file = mkstemp(path);
    char out_path[] = "/tmp/api_values_threads_out_XXXXXX";
    int out_file = mkstemp(out_path);
    fflush(stdout);
    int saved = dup(STDERR_FILENO), saved_out = dup(STDOUT_FILENO);
    if (file < 0 || out_file < 0 || saved < 0 || saved_out < 0 || dup2(file, STDERR_FILENO) < 0 ||
        dup2(out_file, STDOUT_FILENO) < 0) {
        fprintf(stderr, "FAIL: cannot point stderr and stdout at files\n");
        return 1;
    }
    setter s = {.scene = scene};
    loader l = {0};
    pthread_t tid, load_tid;
    bool threaded = pthread_create(&tid, NULL, set_values_loop, &s) == 0;
    bool loading = pthread_create(&load_tid, NULL, load_loop, &l) == 0;
    /* Printed while the other threads set values and load (their first calls before the first line, so that they
     * overlap). */
    while ((threaded && s.sets < 10) || (loading && l.loads < 2)) sched_yield();
    for (int k = 0; k < LINES; ++k) fprintf(stderr, "line %d\n", k), fprintf(stdout, "out %d\n", k);
    atomic_store(&s.stop, true);
    atomic_store(&l.stop, true);
    if (threaded) pthread_join(tid, NULL);
    if (loading) pthread_join(load_tid, NULL);
    fflush(stdout);
    dup2(saved_out, STDOUT_FILENO);
    close(saved_out);
    /* A frame the command line refuses (latitude 95: no place on Earth, the solar position algorithm's range): its
     * line to the callback, on this thread. */
    const char *latitude_flag[1] = {"--latitude"};
    double past_the_pole = 95.0;
    vksky_result refused = vksky_scene_set_values(scene, 1, latitude_flag, &past_the_pole, refused_message, NULL);
    fflush(stderr);
    dup2(saved, STDERR_FILENO);
    close(saved);

    FILE *in = fopen(path, "r");
    /* Lines k in increasing order (a missing one counted), anything else shown. */
    int last = -1, present = 0, others = 0, n;
    char line[1024];
    while (in && fgets(line, sizeof line, in)) {
        if (sscanf(line, "line %d", &n) == 1 && n > last) last = n, ++present;
        else if (others++ < 5) fprintf(stderr, "stderr held: %s", line);
    }
    if (in) fclose(in);
    unlink(path);
    FILE *out_in = fopen(out_path, "r");
    int out_last = -1, out_present = 0, out_others = 0;
    while (out_in && fgets(line, sizeof line, out_in)) {
        if (sscanf(line, "out %d", &n) == 1 && n > out_last) out_last = n, ++out_present;
        else if (out_others++ < 5) fprintf(stderr, "stdout held: %s", line);
    }
    if (out_in) fclose(out_in);
    unlink(out_path);
    HOST_CHECK(loading && l.unexpected == 0, "loads: %ld of %ld not as expected", l.unexpected, l.loads);
    HOST_CHECK(out_present == LINES && out_others == 0, "stdout holds %d of the %d lines and %d other lines (%ld "
               "loads meanwhile)", out_present, LINES, out_others, l.loads);
    HOST_CHECK(threaded, "no second thread");
    HOST_CHECK(s.failures == 0, "%ld of %ld sets failed", s.failures, s.sets);
    HOST_CHECK(present == LINES && others == 0, "stderr holds %d of the %d lines (%d missing) and %d other lines "
               "(%ld sets meanwhile)", present, LINES, LINES - present, others, s.sets);
    HOST_CHECK(refused == VKSKY_ERROR_INVALID_ARGUMENT, "--latitude 95: %s", vksky_result_name(refused));
    HOST_CHECK(refused_count == 1 && pthread_equal(refused_thread, pthread_self()) && strstr(refused_text, "range"),
               "--latitude 95: %d lines to the callback, the last '%s'", refused_count, refused_text);
    vksky_scene_destroy(scene);
    printf("api_values_threads: %d lines printed beside %ld sets and %ld loads: %d in stderr, %d others; %d in "
           "stdout, %d others; refused: '%s'\n", LINES, s.sets, l.loads, present, others, out_present, out_others,
           refused_text);
    return host_failures ? 1 : 0;
}
