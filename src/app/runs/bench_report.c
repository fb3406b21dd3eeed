/* --bench's report (bench_report.h). */
#include "app/runs/bench_report.h"
#include <stdio.h>
#include <stdlib.h>

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void bench_report_print(const bench_figures *b)
{
    int n = b->n;
    if (!n) return;
    if (b->timed) {
        printf("pass transmittance_lut gpu_ms %.4f\n", bench_median(b->lut_ms[0], n));
        if (b->multiscatter) printf("pass multiscatter_lut gpu_ms %.4f\n", bench_median(b->lut_ms[1], n));
        for (int p = 0; p < b->pass_count; ++p) printf("pass %s gpu_ms %.4f\n", b->names[p], bench_median(b->per_pass[p], n));
    }
    printf("frame gpu_ms %.4f wall_ms %.4f\n", b->timed ? bench_median(b->gpu_total, n) : -1.0, bench_median(b->wall, n));
    printf("frame cpu_ms %.4f\n", b->cpu_per_frame);
    printf("frame_luts wall_ms %.4f%s\n", bench_median(b->luts_wall, n), b->async ? " async" : "");
}

void bench_report_sequence(int frames, int outputs, double wall_s, double cpu_ms, int slots, int threads)
{
    printf("sequence frames %d outputs %d wall_s %.3f frames_per_s %.2f cpu_ms_per_frame %.2f readback_slots %d "
           "threads %d\n", frames, outputs, wall_s, frames / wall_s, cpu_ms / frames, slots, threads);
}
