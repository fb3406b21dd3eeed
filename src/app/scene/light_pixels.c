/* An EXR's pixels in output units (light.h: light_exr_pixels_into), fast: a 64 Ki-entry table instead of decoding
 * each half, and the image split over the encode threads. The arithmetic per value is light_exr_pixels' own (the
 * half's value in double, times 1 / light_scale, rounded to float once), so the files keep their bytes. Issue 27: on
 * one thread this conversion was a serial part of every frame (a 720p frame's 3.7 M values) and of every band of a
 * 16384x8192 map (537 M values in all), in front of the parallel encoders. */
#include "app/scene/light.h"
#include "io/parts.h"
#include <math.h>

#define HALF_MAX 65504.0

typedef struct conversion {
    const float *half_value;   /* io_half_table() */
    const uint16_t *in;
    float *out;
    double inv;
    bool over[IO_PARTS_MAX];   /* per part: a value beyond half's range */
} conversion;

static void convert(void *user, size_t part, size_t begin, size_t end)
{
    conversion *c = user;
    bool over = false;
    for (size_t i = 4 * begin; i < 4 * end; ++i) {   /* whole RGBA pixels */
        double v = c->half_value[c->in[i]];
        if (i % 4 != 3) v *= c->inv;   /* alpha is coverage, not light */
        over |= fabs(v) > HALF_MAX;
        c->out[i] = (float)v;
    }
    c->over[part] = over;
}

void light_exr_pixels_into(const options *o, const uint16_t *rgba_half, size_t pixels, float *out, bool *store_float)
{
    conversion c = {io_half_table(), rgba_half, out, 1.0 / light_scale(o), {false}};
    io_parts_run(pixels, 65536, convert, &c);
    bool over = false;
    for (size_t k = 0; k < IO_PARTS_MAX; ++k) over |= c.over[k];
    *store_float = o->exr_type == OPTIONS_EXR_FLOAT || (o->exr_type == OPTIONS_EXR_AUTO && over);
}
