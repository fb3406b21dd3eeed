/* The command line's callbacks for include/vksky.h's messages and trace lines, shared by its API hosts (the headless
 * run, the sequence, the window): a message as one "vksky: ..." line on stderr, a trace line on stdout, as the CLI
 * prints its own. Header-only: each host passes their addresses to the API. */
#ifndef VKSKY_APP_RUNS_HOST_PRINT_H
#define VKSKY_APP_RUNS_HOST_PRINT_H
#include <vksky.h>
#include <stdio.h>

static inline void host_print_message(void *user, vksky_severity severity, const char *message)
{
    (void)user, (void)severity;
    fprintf(stderr, "vksky: %s\n", message);
}

/* --trace-barriers / --trace-passes: the context's trace lines. */
static inline void host_print_trace(void *user, const char *line)
{
    (void)user;
    /* One call, so one locked write into stdout's buffer: the readback ring's consumer prints its own "sync ..." lines
     * to stdout on another thread, and between a fputs and its fputc('\n') one landed inside this line (readback_ring
     * then counted a wait too few: tests/print_lines.c). */
    fprintf(stdout, "%s\n", line);
}
#endif
