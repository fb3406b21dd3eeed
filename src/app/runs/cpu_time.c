#include "app/runs/cpu_time.h"
#include <sys/resource.h>

double process_cpu_ms(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return 1e3 * ((double)u.ru_utime.tv_sec + (double)u.ru_stime.tv_sec) +
           1e-3 * ((double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_usec);
}
