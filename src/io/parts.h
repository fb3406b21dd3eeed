/* vksky image I/O: a conversion over a frame's pixels split over the encode threads (io_encode_threads, --threads).
 * The encoders' neighbours use it: an EXR's halves to output units (app/scene/light_pixels.c) and the spectral
 * groups' sum (app/runs/spectral_host.c). Each part is a range of whole items and runs the same per-item arithmetic
 * as one serial loop would, so the result depends on nothing but the input. */
#ifndef VKSKY_IO_PARTS_H
#define VKSKY_IO_PARTS_H
#include <stddef.h>

/* fn(user, part, begin, end) over items [0, items), in at most io_encode_threads() parts (and at most IO_PARTS_MAX)
 * of at least min_items each (below that a thread costs more than it saves); part 0 runs on the calling thread, as
 * does any part whose thread does not start. Returns when every part is done. `part` numbers the parts from 0, for a
 * caller that keeps a result per part. */
#define IO_PARTS_MAX 64
void io_parts_run(size_t items, size_t min_items, void (*fn)(void *user, size_t part, size_t begin, size_t end),
                  void *user);

/* The 65536 halves' values as floats (io_half_to_float's), built once; safe from any thread. */
const float *io_half_table(void);
#endif
