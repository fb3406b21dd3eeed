/* Graceful stop: see stop.h. The handler only stores the signal's number in a volatile sig_atomic_t (the one kind
 * of object a handler may write); everything else happens on the main path when it next looks at the flag. */
#include "app/runs/stop.h"
#include "io/atomic_file.h"
#include "reference/ref_atmosphere.h"
#include <signal.h>
#include <stdio.h>
#include <string.h>

static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig)
{
    if (!stop_signal) stop_signal = sig;
}

void stop_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    /* SA_RESTART: a system call the signal lands in (a driver's wait, a write) resumes instead of failing with
     * EINTR somewhere we do not check for it. SA_RESETHAND: the handler runs once; a second signal ends the
     * program the default way. */
    sa.sa_flags = SA_RESTART | SA_RESETHAND;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    io_atomic_set_cancel(&stop_signal);
    ref_set_cancel(&stop_signal);   /* the reference's table builds (seconds) stop between rows */
}

bool stop_requested(void) { return stop_signal != 0; }

void stop_print_help(FILE *out)
{
    fprintf(out, "\nexit status: 0 done; 1 a failed render or a validation message; 2 bad input (one line on stderr);\n"
                 "  130 / 143 stopped by SIGINT (Ctrl-C) / SIGTERM: the run stops between frames, after the frame on\n"
                 "  the device, or between pixels (--reference), waits for the device, leaves no partial output and no\n"
                 "  temporary file (a sequence keeps the frames it finished); a second signal ends it at once.\n");
}

int stop_status(int status)
{
    int sig = stop_signal;
    if (!sig) return status;
    fprintf(stderr, "vksky: stopped by %s: exit status %d, no partial output left\n", sig == SIGINT ? "SIGINT" : "SIGTERM",
            128 + sig);
    return 128 + sig;
}
