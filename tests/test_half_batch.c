/* The batch half conversions (F16C where the CPU has it) against an independent reference: every one of the 65536
 * halves decoded by ldexp arithmetic, and a sweep of floats (rounding ties, denormals, overflow, inf, NaN payloads)
 * rounded by a reference written from the IEEE 754 definition (nearest, ties to even, on exact rationals), plus
 * bit-identity with the scalar io_float_to_half / io_half_to_float. */
#include "io/half_float.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint32_t fbits(float f)
{
    uint32_t x;
    memcpy(&x, &f, sizeof x);
    return x;
}
static float bitsf(uint32_t x)
{
    float f;
    memcpy(&f, &x, sizeof f);
    return f;
}

/* Independent half -> double: sign * m * 2^(e-25) style decoding from the definition. */
static double half_value(uint16_t h)
{
    int e = (h >> 10) & 31, m = h & 1023;
    double v = e == 0 ? ldexp(m, -24) : ldexp(1024 + m, e - 25);
    return (h & 0x8000) ? -v : v;
}

/* Independent float -> half for finite floats: the nearest half by value (ties to the even mantissa), finite values
 * beyond 65504 clamped to 65504, as half_float.h documents. */
static uint16_t ref_to_half(float f)
{
    uint16_t sign = signbit(f) ? 0x8000 : 0;
    double a = fabs((double)f);
    if (a > 65504.0) return sign | 0x7bff;
    /* halves are monotone in their bits for non-negative values: binary search the bracket. */
    uint16_t lo = 0, hi = 0x7bff;
    while (hi - lo > 1) {
        uint16_t mid = (uint16_t)((lo + hi) / 2);
        if (half_value(mid) <= a) lo = mid; else hi = mid;
    }
    if (half_value(hi) <= a) lo = hi;
    if (lo == 0x7bff) return sign | lo;
    double dl = a - half_value(lo), dh = half_value((uint16_t)(lo + 1)) - a;
    uint16_t r = dl < dh ? lo : dh < dl ? (uint16_t)(lo + 1) : (lo & 1) ? (uint16_t)(lo + 1) : lo;
    return sign | r;
}

static int failures;
#define CHECK(c, ...) do { if (!(c)) { if (failures++ < 20) { fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); } } } while (0)

static void run(const char *label)
{
    /* 1. every half -> float */
    uint16_t *hs = malloc(65536 * sizeof *hs);
    float *fs = malloc(65536 * sizeof *fs);
    for (uint32_t i = 0; i < 65536; ++i) hs[i] = (uint16_t)i;
    io_halves_to_floats(fs, hs, 65536);
    for (uint32_t i = 0; i < 65536; ++i) {
        uint16_t h = (uint16_t)i;
        CHECK(fbits(fs[i]) == fbits(io_half_to_float(h)), "%s: half %04x batch %08x scalar %08x", label, h,
              fbits(fs[i]), fbits(io_half_to_float(h)));
        int e = (h >> 10) & 31;
        if (e != 31) CHECK((double)fs[i] == half_value(h) && !!signbit(fs[i]) == !!(h & 0x8000),
                           "%s: half %04x -> %g, want %g", label, h, fs[i], half_value(h));
        else if ((h & 1023) == 0) CHECK(isinf(fs[i]), "%s: half %04x not inf", label, h);
        else CHECK(isnan(fs[i]) && ((fbits(fs[i]) >> 13) & 1023) == (h & 1023u),
                   "%s: half %04x NaN payload lost", label, h);
    }
    /* 2. float sweep: every half and the midpoints/neighbours around it, denormals, beyond 65504, inf, NaN */
    size_t cap = 65536 * 8 + 64, n = 0;
    float *in = malloc(cap * sizeof *in);
    for (uint32_t i = 0; i < 0x7c00; ++i) {
        double v = half_value((uint16_t)i), nx = half_value((uint16_t)(i + 1 < 0x7c00 ? i + 1 : i));
        float mid = (float)((v + nx) / 2); /* exact: a tie */
        float vals[4] = {mid, nextafterf(mid, 0), nextafterf(mid, INFINITY), (float)v};
        for (int k = 0; k < 4; ++k) { in[n++] = vals[k]; in[n++] = -vals[k]; }
    }
    float extra[] = {65504.f, 65505.f, 65519.f, 65519.996f, 65520.f, 65536.f, 1e10f, 3.4e38f, INFINITY, -INFINITY,
                     bitsf(0x7fc00000u), bitsf(0xffc00001u), bitsf(0x7f800001u), bitsf(0x7fa02000u),
                     bitsf(0x00000001u), bitsf(0x80000001u), 1e-30f, 2.98e-8f, 2.9802322e-8f, 5.96e-8f};
    for (size_t k = 0; k < sizeof extra / sizeof *extra; ++k) in[n++] = extra[k];
    uint16_t *out = malloc(n * sizeof *out);
    io_floats_to_halves(out, in, n, 1);
    for (size_t i = 0; i < n; ++i) {
        uint16_t s = io_float_to_half(in[i]);
        CHECK(out[i] == s, "%s: float %08x batch %04x scalar %04x", label, fbits(in[i]), out[i], s);
        if (isnan(in[i])) CHECK((out[i] & 0x7e00) == 0x7e00 && (out[i] & 0x1ff) == ((fbits(in[i]) >> 13) & 0x1ff),
                                "%s: NaN %08x -> %04x", label, fbits(in[i]), out[i]);
        else if (isinf(in[i])) CHECK((out[i] & 0x7fff) == 0x7c00, "%s: inf -> %04x", label, out[i]);
        else CHECK(out[i] == ref_to_half(in[i]), "%s: float %.9g (%08x) -> %04x, reference %04x", label, in[i],
                   fbits(in[i]), out[i], ref_to_half(in[i]));
    }
    /* 3. strided input (a channel of interleaved RGBA) gives the same as contiguous */
    uint16_t *st = malloc((n / 4) * sizeof *st);
    io_floats_to_halves(st, in + 1, n / 4, 4);
    for (size_t i = 0; i < n / 4; ++i) CHECK(st[i] == io_float_to_half(in[1 + 4 * i]), "%s: stride at %zu", label, i);
    free(st), free(out), free(in), free(fs), free(hs);
}

int main(void)
{
    printf("f16c: %s\n", io_half_uses_f16c() ? "yes" : "no");
    run(io_half_uses_f16c() ? "f16c" : "portable");
    setenv("VKSKY_NO_F16C", "1", 1);
    run("portable");
    if (failures) {
        fprintf(stderr, "test_half_batch: %d failures\n", failures);
        return 1;
    }
    printf("test_half_batch: ok\n");
    return 0;
}
