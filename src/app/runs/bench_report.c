/* --bench's figures and report (bench_report.h). */
#include "app/runs/bench_report.h"
#include "app/runs/cpu_time.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int bench_figures_begin(bench_figures *b, int n)
{
    *b = (bench_figures){.n = n, .timed = true};
    size_t count = (size_t)(n > 0 ? n : 1);
    b->lut_ms[0] = calloc(count, sizeof(double)), b->lut_ms[1] = calloc(count, sizeof(double));
    b->luts_wall = calloc(count, sizeof(double));
    b->gpu_total = calloc(count, sizeof(double)), b->wall = calloc(count, sizeof(double));
    return b->lut_ms[0] && b->lut_ms[1] && b->luts_wall && b->gpu_total && b->wall ? 0 : 1;
}

void bench_figures_lut_pass(bench_figures *b, int frame, const char *name, double ms)
{
    if (!strcmp(name, "transmittance_lut")) b->lut_ms[0][frame] = ms;
    if (!strcmp(name, "multiscatter_lut")) b->lut_ms[1][frame] = ms, b->multiscatter = true;
}

void bench_figures_pass(bench_figures *b, int frame, const char *name, double ms)
{
    int slot = -1;
    for (int p = 0; p < b->pass_count; ++p)
        if (!strcmp(b->names[p], name)) slot = p;
    if (slot < 0 && b->pass_count < BENCH_MAX_PASSES) {
        double *per_frame = calloc((size_t)b->n, sizeof(double));
        if (per_frame) slot = b->pass_count++, b->names[slot] = name, b->per_pass[slot] = per_frame;
    }
    if (slot >= 0) b->per_pass[slot][frame] += ms;   /* repeated passes (bloom) add up per frame */
    b->gpu_total[frame] += ms;
}

void bench_report_print(bench_figures *b, int frames)
{
    int n = frames;
    if (!n) return;
    double cpu_per_frame = (process_cpu_ms() - b->cpu_start) / n;
    if (b->timed) {
        printf("pass transmittance_lut gpu_ms %.4f\n", bench_median(b->lut_ms[0], n));
        if (b->multiscatter) printf("pass multiscatter_lut gpu_ms %.4f\n", bench_median(b->lut_ms[1], n));
        for (int p = 0; p < b->pass_count; ++p)
            printf("pass %s gpu_ms %.4f\n", b->names[p], bench_median(b->per_pass[p], n));
    }
    printf("frame gpu_ms %.4f wall_ms %.4f\n", b->timed ? bench_median(b->gpu_total, n) : -1.0,
           bench_median(b->wall, n));
    printf("frame cpu_ms %.4f\n", cpu_per_frame);
    printf("frame_luts wall_ms %.4f%s\n", bench_median(b->luts_wall, n), b->async ? " async" : "");
}

void bench_figures_end(bench_figures *b)
{
    for (int p = 0; p < b->pass_count; ++p) free(b->per_pass[p]);
    free(b->lut_ms[0]), free(b->lut_ms[1]), free(b->luts_wall), free(b->gpu_total), free(b->wall);
    *b = (bench_figures){0};
}

void bench_report_sequence(int frames, int outputs, double wall_s, double cpu_ms, int slots, int threads)
{
    printf("sequence frames %d outputs %d wall_s %.3f frames_per_s %.2f cpu_ms_per_frame %.2f readback_slots %d "
           "threads %d\n", frames, outputs, wall_s, frames / wall_s, cpu_ms / frames, slots, threads);
}
