/* vksky image I/O: IEEE half-float conversion. See half_float.h. */
#include "io/half_float.h"

#include <string.h>

uint16_t io_float_to_half(float f)
{
    uint32_t x;
    memcpy(&x, &f, sizeof x);
    uint16_t sign = (uint16_t)((x >> 16) & 0x8000u);
    uint32_t ax = x & 0x7fffffffu;

    if (ax >= 0x7f800000u) {
        if (ax == 0x7f800000u) return (uint16_t)(sign | 0x7c00u); /* infinity */
        return (uint16_t)(sign | 0x7e00u | ((ax >> 13) & 0x3ffu)); /* NaN: quiet, keep top payload bits */
    }
    if (ax > 0x477fe000u) return (uint16_t)(sign | 0x7bffu); /* > 65504: clamp to max finite */

    uint32_t e = ax >> 23;
    if (e < 113) {
        /* Result is a half denormal (or zero, or rounds up to the smallest normal). */
        if (e < 102) return sign; /* < 2^-25: rounds to zero */
        uint32_t m = (ax & 0x7fffffu) | 0x800000u;
        uint32_t shift = 126u - e; /* 14..24 */
        uint32_t h = m >> shift;
        uint32_t rem = m & ((1u << shift) - 1u);
        uint32_t halfway = 1u << (shift - 1u);
        if (rem > halfway || (rem == halfway && (h & 1u))) ++h;
        return (uint16_t)(sign | h);
    }
    /* Normal: rebias exponent (127 -> 15), round mantissa 23 -> 10 bits; carries ripple into the exponent. */
    uint32_t h = ((e - 112u) << 10) | ((ax >> 13) & 0x3ffu);
    uint32_t rem = ax & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;
    return (uint16_t)(sign | h);
}

float io_half_to_float(uint16_t hv)
{
    uint32_t sign = (uint32_t)(hv & 0x8000u) << 16;
    uint32_t e = (hv >> 10) & 0x1fu;
    uint32_t m = hv & 0x3ffu;
    uint32_t x;
    if (e == 0x1fu) {
        x = sign | 0x7f800000u | (m << 13); /* inf / NaN (payload kept) */
    } else if (e != 0) {
        x = sign | ((e + 112u) << 23) | (m << 13);
    } else if (m == 0) {
        x = sign;
    } else {
        /* Denormal: normalise. */
        uint32_t ee = 113;
        while (!(m & 0x400u)) {
            m <<= 1;
            --ee;
        }
        x = sign | (ee << 23) | ((m & 0x3ffu) << 13);
    }
    float f;
    memcpy(&f, &x, sizeof f);
    return f;
}
