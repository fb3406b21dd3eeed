/* scene_mutate IN.json SEED: print a mutated copy of a scene file (a helper of tests/scene_fuzz.sh). 1 to 4
 * mutations, chosen by SEED (same seed, same output): delete a byte range, insert a hostile token (broken JSON
 * punctuation, huge/tiny/non-finite numbers, wrong types, NUL and control bytes, profile and species snippets),
 * replace a number with one, duplicate or truncate a stretch. Exit 2 on bad arguments, 1 if IN is unreadable. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng;
static uint64_t next(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return rng;
}
static size_t below(size_t n) { return n ? (size_t)(next() % n) : 0; }

static const char *const tokens[] = {
    "\"", "{", "}", "[", "]", ",", ":", "-1e309", "1e400", "NaN", "-nan", "Infinity", "null", "true", "false",
    "\"x\"", "0", "-0", "1e-320", "4.9e-324", "99999999999999999999999", "-1", "0.5", "1000", "1e6", "170", "-90",
    "16384", "[]", "{}", "[0, 0]", "[1e308, 1e308, 1e308]", "\"layers\"", "\"tent\"", "\"exponential\"",
    "{\"layers\": [{\"exp_term\": 1000, \"exp_scale_per_km\": 1000}]}", "{\"layers\": []}",
    "{\"profile\": \"layers\", \"layers\": [{}, {}, {}]}", "\"gas\": {\"absorption\": [1, 1, 1], \"density\": {}},",
    "\"a\": {\"absorption\": [0, 0, 1e-3], \"density\": {\"scale_height_km\": 1}},", "\"\\u0000\"", "\"\\ud800\"",
    "\x01", "\xff\xfe", "//", "/*", "\n", "\t", "\"preset\": \"ultra\",", "\"multiscatter_lut\": 1024,",
    "\"width\": 16384, \"height\": 16384,"};

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: scene_mutate IN.json SEED\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) return 1;
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf / 2, f);
    fclose(f);
    rng = 0x9E3779B97F4A7C15ull ^ strtoull(argv[2], NULL, 10) * 0xBF58476D1CE4E5B9ull;
    for (int i = 0; i < 16; ++i) next();
    int mutations = 1 + (int)below(4);
    for (int m = 0; m < mutations && n < sizeof buf / 2; ++m) {
        size_t at = below(n + 1);
        switch (below(5)) {
        case 0: { /* delete */
            size_t len = 1 + below(8);
            if (at + len > n) len = n - at;
            memmove(buf + at, buf + at + len, n - at - len);
            n -= len;
            break;
        }
        case 1: { /* insert a token */
            const char *t = tokens[below(sizeof tokens / sizeof tokens[0])];
            size_t len = strlen(t);
            memmove(buf + at + len, buf + at, n - at);
            memcpy(buf + at, t, len);
            n += len;
            break;
        }
        case 2: { /* replace the next number with a token */
            while (at < n && !(buf[at] >= '0' && buf[at] <= '9')) ++at;
            size_t end = at;
            while (end < n && strchr("0123456789.eE+-", buf[end])) ++end;
            const char *t = tokens[7 + below(21)];
            size_t len = strlen(t);
            memmove(buf + at + len, buf + end, n - end);
            memcpy(buf + at, t, len);
            n = n - (end - at) + len;
            break;
        }
        case 3: { /* duplicate a stretch */
            size_t len = 1 + below(64);
            if (at + len > n) len = n - at;
            memmove(buf + at + len, buf + at, n - at);
            n += len;
            break;
        }
        default: /* truncate */
            if (below(4) == 0) n = at;
            break;
        }
    }
    fwrite(buf, 1, n, stdout);
    return 0;
}
