/* vksky image I/O: IEEE half-float conversion. See half_float.h. */
#include "io/half_float.h"

#include <stdlib.h>
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

/* Batch conversion. On x86 with F16C the hardware converts four values at a time; the results are made bit-identical
 * to the scalar functions above (tests/test_half_batch.c checks every half and a float sweep):
 *  - float -> half: F16C rounds finite values above 65504 to infinity, we clamp them to 65504 first;
 *    NaNs are quieted with the top payload bits kept, exactly as io_float_to_half does.
 *  - half -> float: F16C quiets signalling NaNs, io_half_to_float keeps the payload as is, so a group of four that
 *    holds a NaN goes through the scalar path (NaNs are rare in images). */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#include <immintrin.h>
#define IO_HALF_HAVE_F16C 1

__attribute__((target("sse2,f16c"))) static void floats_to_halves_f16c(uint16_t *dst, const float *src, size_t n,
                                                                       size_t stride)
{
    const __m128i absmask = _mm_set1_epi32(0x7fffffff), maxf = _mm_set1_epi32(0x477fe000);
    const __m128i inf = _mm_set1_epi32(0x7f800000);
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        __m128 v = stride == 1 ? _mm_loadu_ps(src + i)
                               : _mm_setr_ps(src[i * stride], src[(i + 1) * stride], src[(i + 2) * stride],
                                             src[(i + 3) * stride]);
        __m128i x = _mm_castps_si128(v);
        __m128i ax = _mm_and_si128(x, absmask);
        /* finite and above 65504: replace the magnitude by 65504, keep the sign. */
        __m128i big = _mm_and_si128(_mm_cmpgt_epi32(ax, maxf), _mm_cmpgt_epi32(inf, ax));
        __m128i clamped = _mm_or_si128(_mm_andnot_si128(absmask, x), maxf);
        x = _mm_or_si128(_mm_and_si128(big, clamped), _mm_andnot_si128(big, x));
        __m128i h = _mm_cvtps_ph(_mm_castsi128_ps(x), _MM_FROUND_TO_NEAREST_INT);
        _mm_storel_epi64((__m128i *)(void *)(dst + i), h);
    }
    for (; i < n; ++i) dst[i] = io_float_to_half(src[i * stride]);
}

__attribute__((target("sse2,f16c"))) static void halves_to_floats_f16c(float *dst, const uint16_t *src, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        uint64_t bits;
        memcpy(&bits, src + i, sizeof bits);
        /* A lane with exponent 31 and a non-zero mantissa is a NaN. */
        int nan = 0;
        for (int k = 0; k < 4; ++k) {
            uint16_t h = (uint16_t)(bits >> (16 * k));
            nan |= (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu) != 0;
        }
        if (nan) {
            for (int k = 0; k < 4; ++k) dst[i + k] = io_half_to_float(src[i + k]);
            continue;
        }
        _mm_storeu_ps(dst + i, _mm_cvtph_ps(_mm_cvtsi64_si128((long long)bits)));
    }
    for (; i < n; ++i) dst[i] = io_half_to_float(src[i]);
}

static int have_f16c(void)
{
    static int cached = -1; /* benign race: every thread computes the same answer */
    if (cached < 0) {
        /* cpuid rather than __builtin_cpu_supports("f16c"), which clang 14 does not know. F16C is VEX-encoded: it
         * also needs the OS to save the AVX state (OSXSAVE and XCR0's SSE and AVX bits). */
        unsigned a = 0, b = 0, c = 0, d = 0;
        int ok = __get_cpuid(1, &a, &b, &c, &d) && (c & (1u << 29)) && (c & (1u << 28)) && (c & (1u << 27));
        if (ok) {
            unsigned lo, hi;
            __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
            ok = (lo & 6u) == 6u;
        }
        cached = ok;
    }
    return cached;
}
#endif

static int use_f16c(void)
{
#ifdef IO_HALF_HAVE_F16C
    const char *off = getenv("VKSKY_NO_F16C"); /* lets tests compare the portable path */
    return have_f16c() && !(off && off[0] && off[0] != '0');
#else
    return 0;
#endif
}

void io_floats_to_halves(uint16_t *dst, const float *src, size_t n, size_t src_stride)
{
    if (src_stride == 0) src_stride = 1;
#ifdef IO_HALF_HAVE_F16C
    if (use_f16c()) {
        floats_to_halves_f16c(dst, src, n, src_stride);
        return;
    }
#endif
    for (size_t i = 0; i < n; ++i) dst[i] = io_float_to_half(src[i * src_stride]);
}

void io_halves_to_floats(float *dst, const uint16_t *src, size_t n)
{
#ifdef IO_HALF_HAVE_F16C
    if (use_f16c()) {
        halves_to_floats_f16c(dst, src, n);
        return;
    }
#endif
    for (size_t i = 0; i < n; ++i) dst[i] = io_half_to_float(src[i]);
}

int io_half_uses_f16c(void)
{
    return use_f16c();
}
