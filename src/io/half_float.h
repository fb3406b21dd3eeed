/* vksky image I/O: IEEE 754 binary16 ("half") conversion, the EXR writer's pixel format. */
#ifndef VKSKY_IO_HALF_FLOAT_H
#define VKSKY_IO_HALF_FLOAT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* float <-> half (round to nearest even, clamp finite values to +-65504, infinities stay infinite, NaN stays NaN). */
uint16_t io_float_to_half(float f);
float io_half_to_float(uint16_t h);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_HALF_FLOAT_H */
