/* Graceful stop (issue 15): SIGINT and SIGTERM set a flag and nothing else; the long-running paths (the window loop,
 * headless frames and --bench, sequences, the reference's table rows and pixels) check it between units of work,
 * then wait for the device, destroy what they made, write no output and leave no temporary file, and exit with
 * 128 + the signal's number (130 for SIGINT, 143 for SIGTERM) after one line on stderr. A second signal, after the
 * first was caught, takes its default action (ends the program at once), for a run that does not stop quickly
 * enough. */
#ifndef VKSKY_APP_STOP_H
#define VKSKY_APP_STOP_H
#include <stdbool.h>
#include <stdio.h>

/* Installs the handlers for SIGINT and SIGTERM, and hands io the flag (an output not yet renamed into place is
 * then abandoned) and the reference (a table being built is then left unfinished). Call at the start of a
 * long-running mode. */
void stop_install(void);

/* A stop was asked for (async-signal-safe read of the flag). */
bool stop_requested(void);

/* The exit status for a run that ended with `status`: when a stop was asked for, prints one line on stderr ("vksky:
 * stopped by SIGINT (...)") and returns 128 + the signal; otherwise returns `status` unchanged. */
int stop_status(int status);

/* --help's last paragraph: the exit statuses, and what a stop does. */
void stop_print_help(FILE *out);
#endif
