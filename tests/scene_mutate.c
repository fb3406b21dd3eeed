/* scene_mutate IN.json SEED: print a mutated copy of a scene file (a helper of tests/scene_fuzz.sh). 1 to 4
 * mutations, chosen by SEED (same seed, same output): delete a byte range, insert a hostile token (broken JSON
 * punctuation, huge/tiny/non-finite numbers, wrong types, NUL and control bytes, profile and species snippets),
 * replace a number with one, duplicate or truncate a stretch.
 * scene_mutate IN.json FIRST LAST DIR: the mutants of seeds FIRST..LAST, each the very bytes the first form prints,
 * into DIR/m<SEED>.json (one process for a scene's hundreds of mutants: scene_fuzz.sh, issue 27 item 5).
 * Exit 2 on bad arguments, 1 if IN is unreadable or a mutant cannot be written. */
#include <stdint.h>
#include <errno.h>
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

/* The mutant of seed `seed` of the scene in buf (n bytes), in place (buf holds twice the input's room); its length. */
static size_t mutate(char *buf, size_t n, size_t room, unsigned long long seed)
{
    rng = 0x9E3779B97F4A7C15ull ^ seed * 0xBF58476D1CE4E5B9ull;
    for (int i = 0; i < 16; ++i) next();
    int mutations = 1 + (int)below(4);
    for (int m = 0; m < mutations && n < room / 2; ++m) {
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
    return n;
}

static int seed_arg(const char *s, unsigned long long *out)
{
    char *end;
    errno = 0;
    *out = strtoull(s, &end, 10);
    return errno == 0 && end != s && *end == '\0';
}

int main(int argc, char **argv)
{
    unsigned long long first = 0, last = 0;
    if (!(argc == 3 && seed_arg(argv[2], &first)) &&
        !(argc == 5 && seed_arg(argv[2], &first) && seed_arg(argv[3], &last) && first <= last)) {
        fprintf(stderr, "usage: scene_mutate IN.json SEED | scene_mutate IN.json FIRST LAST DIR\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) return 1;
    static char input[1 << 19], buf[1 << 20];
    size_t in_n = fread(input, 1, sizeof input, f);
    fclose(f);
    if (argc == 3) {
        memcpy(buf, input, in_n);
        fwrite(buf, 1, mutate(buf, in_n, sizeof buf, first), stdout);
        return 0;
    }
    for (unsigned long long seed = first; seed <= last; ++seed) {
        memcpy(buf, input, in_n);
        size_t n = mutate(buf, in_n, sizeof buf, seed);
        char path[4096];
        snprintf(path, sizeof path, "%s/m%llu.json", argv[4], seed);
        FILE *out = fopen(path, "wb");
        if (!out || fwrite(buf, 1, n, out) != n || fclose(out) != 0) {
            fprintf(stderr, "scene_mutate: cannot write %s\n", path);
            return 1;
        }
    }
    return 0;
}
