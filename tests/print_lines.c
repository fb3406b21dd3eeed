/* The command line's trace callback (app/runs/host_print.h) writes whole lines while another thread prints to stdout
 * (the readback ring's consumer prints its "sync ..." lines beside the producer's recorded trace): stdout pointed at a
 * file, one thread prints 100000 "sync N" lines, the other 100000 trace lines through host_print_trace; every line of
 * the file is one of the two kinds, whole (readback_ring's flake: a "sync" line landed inside a trace line, between
 * its text and its newline, and ^sync counted one too few). No GPU. */
#include "app/runs/host_print.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { LINES = 100000 };

static void *sync_lines(void *arg)
{
    (void)arg;
    for (int k = 0; k < LINES; ++k) fprintf(stdout, "sync ring.gpu_done frame=%d\n", k);
    return NULL;
}

int main(void)
{
    char path[] = "/tmp/print_lines_XXXXXX";
    int file = mkstemp(path);
    int saved = dup(STDOUT_FILENO);
    fflush(stdout);
    if (file < 0 || saved < 0 || dup2(file, STDOUT_FILENO) < 0) {
        fprintf(stderr, "FAIL: cannot point stdout at a file\n");
        return 1;
    }
    pthread_t tid;
    bool threaded = pthread_create(&tid, NULL, sync_lines, NULL) == 0;
    for (int k = 0; k < LINES; ++k) host_print_trace(NULL, "barrier frame.readback writer=copy reader=host hazard=RAW");
    if (threaded) pthread_join(tid, NULL);
    fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    FILE *in = fopen(path, "r");
    char line[512];
    int sync = 0, trace = 0, torn = 0;
    while (in && fgets(line, sizeof line, in)) {
        if (!strncmp(line, "sync ring.gpu_done frame=", 25) && !strchr(line + 25, ' ')) ++sync;
        else if (!strcmp(line, "barrier frame.readback writer=copy reader=host hazard=RAW\n")) ++trace;
        else if (torn++ < 3) fprintf(stderr, "torn line: %s", line);
    }
    if (in) fclose(in);
    unlink(path);
    bool ok = threaded && sync == LINES && trace == LINES && torn == 0;
    printf("print_lines: %d sync lines, %d trace lines whole of %d each; %d other lines\n", sync, trace, LINES, torn);
    return ok ? 0 : 1;
}
