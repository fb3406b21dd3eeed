/* The readback ring's rules (issue 27: several frames encoding at once), for app/runs/host_ring.h, the command line's
 * ring as a host of include/vksky.h (its own ring over the renderer, frame_ring.c, went in 25i). No src/sky or
 * src/lib header (host_ring.c is an API host: tests/layering_test.sh). */
#ifndef VKSKY_APP_RING_ORDER_H
#define VKSKY_APP_RING_ORDER_H

/* Frames encoded at once (consumer threads) for images of `pixels`, at most `max`: VKSKY_ENCODE_FRAMES if set
 * (1..max), else one per 4 encode threads (--threads, default the cores: 16 cores -> 3 frames of 5 threads each),
 * and no more than ~1 GiB of frames in flight. 1 on a 2-core machine: one consumer. */
int ring_consumers_wanted(long pixels, int max);
/* VKSKY_RING_DELAY_MS ("MS" or "EVEN:ODD"): how long a consumer dawdles over even and odd frames (tests: widens races,
 * and with EVEN > ODD frames encoded at once finish out of order). */
void ring_delays(int *even_ms, int *odd_ms);
#endif
