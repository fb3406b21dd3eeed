/* An EXR's pixels in output units (light.h: light_exr_pixels_into), fast: a 64 Ki-entry table instead of decoding
 * each half, and the image split over the encode threads. The arithmetic per value is light_exr_pixels' own (the
 * half's value in double, times 1 / light_scale, rounded to float once), so the files keep their bytes. Issue 27: on
 * one thread this conversion was a serial part of every frame (a 720p frame's 3.7 M values) and of every band of a
 * 16384x8192 map (537 M values in all), in front of the parallel encoders. */
#include "app/scene/light.h"
#include "io/encode_settings.h"
#include "io/half_float.h"
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#define HALF_MAX 65504.0
#define MAX_PARTS 64

static float half_table[65536];
static pthread_once_t table_once = PTHREAD_ONCE_INIT;

static void table_init(void)
{
    for (uint32_t h = 0; h < 65536; ++h) half_table[h] = io_half_to_float((uint16_t)h);
}

typedef struct part {
    const uint16_t *in;
    float *out;
    size_t values;   /* a multiple of 4: whole RGBA pixels */
    double inv;
    bool over;
} part;

static void *convert(void *arg)
{
    part *p = arg;
    bool over = false;
    for (size_t i = 0; i < p->values; ++i) {
        double v = half_table[p->in[i]];
        if (i % 4 != 3) v *= p->inv;   /* alpha is coverage, not light */
        over |= fabs(v) > HALF_MAX;
        p->out[i] = (float)v;
    }
    p->over = over;
    return NULL;
}

void light_exr_pixels_into(const options *o, const uint16_t *rgba_half, size_t pixels, float *out, bool *store_float)
{
    pthread_once(&table_once, table_init);
    double inv = 1.0 / light_scale(o);
    /* Parts of at least 64 Ki pixels: below that a thread costs more than it saves. */
    size_t parts = (size_t)io_encode_threads();
    if (parts > MAX_PARTS) parts = MAX_PARTS;
    if (parts > pixels / 65536) parts = pixels / 65536;
    if (parts < 1) parts = 1;
    part p[MAX_PARTS];
    pthread_t tid[MAX_PARTS];
    size_t per = pixels / parts, at = 0;
    for (size_t k = 0; k < parts; ++k) {
        size_t n = k + 1 == parts ? pixels - at : per;
        p[k] = (part){rgba_half + at * 4, out + at * 4, n * 4, inv, false};
        at += n;
    }
    size_t started = 1;   /* part 0 on this thread */
    for (; started < parts; ++started)
        if (pthread_create(&tid[started], NULL, convert, &p[started]) != 0) break;
    for (size_t k = started; k < parts; ++k) convert(&p[k]);   /* threads that did not start */
    convert(&p[0]);
    bool over = p[0].over;
    for (size_t k = 1; k < parts; ++k) {
        if (k < started) pthread_join(tid[k], NULL);
        over |= p[k].over;
    }
    *store_float = o->exr_type == OPTIONS_EXR_FLOAT || (o->exr_type == OPTIONS_EXR_AUTO && over);
}
