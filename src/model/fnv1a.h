/* FNV-1a, 64-bit (Fowler, Noll and Vo; offset basis and prime from the authors' reference): the hash of the keys
 * that name a medium's cached results, the sky's LUT cache (sky/atmosphere.c) and the reference's Psi tables on
 * disk (reference/psi_disk.c). Not a checksum against attack: a key names what a file holds, and each reader
 * compares the stored key in full as well. (src/gpu keeps its own copy for the pipeline cache: the GPU layer sits
 * below nothing of the model's.) */
#ifndef VKSKY_MODEL_FNV1A_H
#define VKSKY_MODEL_FNV1A_H

#include <stddef.h>
#include <stdint.h>

#define MODEL_FNV1A_OFFSET 1469598103934665603ull

/* h continued over `size` bytes of `data`; start from MODEL_FNV1A_OFFSET. */
static inline uint64_t model_fnv1a(uint64_t h, const void *data, size_t size)
{
    const unsigned char *bytes = data;
    for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

#endif
