/* The readback rings' shared rules (ring_order.h). */
#include "app/runs/ring_order.h"
#include "io/encode_settings.h"
#include <stdlib.h>
#include <string.h>

int ring_consumers_wanted(long pixels, int max)
{
    const char *env = getenv("VKSKY_ENCODE_FRAMES");
    int n = env && *env ? atoi(env) : io_encode_threads_all() / 4;
    if (!(env && *env)) {
        /* In flight per frame: a slot (12 bytes a pixel) and the EXR's float copy (16): ~1 GiB in all at most. */
        long cap = pixels > 0 ? (1L << 30) / (pixels * 28) : 1;
        if (n > cap) n = (int)cap;
    }
    return n < 1 ? 1 : n > max ? max : n;
}

void ring_delays(int *even_ms, int *odd_ms)
{
    const char *delay = getenv("VKSKY_RING_DELAY_MS");
    *even_ms = delay ? atoi(delay) : 0;
    const char *odd = delay ? strchr(delay, ':') : NULL;
    *odd_ms = odd ? atoi(odd + 1) : *even_ms;
}
