/* vksky image I/O: IEEE 754 binary16 ("half") conversion, the EXR writer's pixel format. */
#ifndef VKSKY_IO_HALF_FLOAT_H
#define VKSKY_IO_HALF_FLOAT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* float <-> half (round to nearest even, clamp finite values to +-65504, infinities stay infinite, NaN stays NaN). */
uint16_t io_float_to_half(float f);
float io_half_to_float(uint16_t h);

/* n values at once, bit-identical to the functions above; F16C where the CPU has it (VKSKY_NO_F16C=1 forces the
   portable path). src_stride: distance in floats between consecutive inputs (1 = contiguous; 0 is taken as 1). */
void io_floats_to_halves(uint16_t *dst, const float *src, size_t n, size_t src_stride);
void io_halves_to_floats(float *dst, const uint16_t *src, size_t n);
/* 1 when the batch functions use F16C. */
int io_half_uses_f16c(void);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_HALF_FLOAT_H */
