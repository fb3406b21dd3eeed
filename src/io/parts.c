/* vksky image I/O: conversions over pixel ranges on the encode threads (parts.h). */
#include "io/parts.h"
#include "io/encode_settings.h"
#include "io/half_float.h"
#include <pthread.h>
#include <stdint.h>

typedef struct part_arg {
    void (*fn)(void *user, size_t part, size_t begin, size_t end);
    void *user;
    size_t part, begin, end;
} part_arg;

static void *part_main(void *arg)
{
    const part_arg *a = arg;
    a->fn(a->user, a->part, a->begin, a->end);
    return NULL;
}

void io_parts_run(size_t items, size_t min_items, void (*fn)(void *user, size_t part, size_t begin, size_t end),
                  void *user)
{
    size_t parts = (size_t)io_encode_threads();
    if (parts > IO_PARTS_MAX) parts = IO_PARTS_MAX;
    if (min_items > 0 && parts > items / min_items) parts = items / min_items;
    if (parts < 1) parts = 1;
    part_arg p[IO_PARTS_MAX];
    pthread_t tid[IO_PARTS_MAX];
    size_t per = items / parts, at = 0;
    for (size_t k = 0; k < parts; ++k) {
        size_t n = k + 1 == parts ? items - at : per;
        p[k] = (part_arg){fn, user, k, at, at + n};
        at += n;
    }
    size_t started = 1;   /* part 0 on this thread */
    for (; started < parts; ++started)
        if (pthread_create(&tid[started], NULL, part_main, &p[started]) != 0) break;
    for (size_t k = started; k < parts; ++k) part_main(&p[k]);   /* parts whose thread did not start */
    part_main(&p[0]);
    for (size_t k = 1; k < started; ++k) pthread_join(tid[k], NULL);
}

static float half_table[65536];
static pthread_once_t half_table_once = PTHREAD_ONCE_INIT;

static void half_table_init(void)
{
    for (uint32_t h = 0; h < 65536; ++h) half_table[h] = io_half_to_float((uint16_t)h);
}

const float *io_half_table(void)
{
    pthread_once(&half_table_once, half_table_init);
    return half_table;
}
