/* Psi tables on disk, for the test suite (VKSKY_PSI_CACHE=DIR): many test processes judge the GPU against the same
 * atmosphere at the converged counts, and each built the same Psi table (the default Earth's 57 times in one suite
 * run: 124 s of wall time on 2 cores, docs/performance.md "The test suite's own time"). With the variable set,
 * psi_cache_get (psi_table.c) loads a table that an earlier process of the run stored and stores the ones it builds.
 *
 * A file holds the key (a version, the table's dimensions and size, the Psi counts and the atmosphere's bytes as the
 * in-memory cache compares them), the table, and an FNV-1a checksum of both; anything else (another key, a short,
 * long or corrupt file, an unreadable directory) is a miss, and the table is built as without the variable. Writes
 * are atomic (a temporary file, then rename), so processes running side by side read a whole file or none. The file
 * does not know which build wrote it: the suite empties the directory at the start of every run (the lut_cache_reset
 * fixture, tests/CMakeLists.txt), so a run only reads tables built by its own build. Not for users' directories. */
#include "model/fnv1a.h"
#include "reference/ref_internal.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PSI_DISK_VERSION 1u

typedef struct psi_disk_key {
    char magic[8];               /* "vkskyPsi" */
    uint32_t version, table_bytes;
    int32_t sqrt_dirs, steps;
    model_atmosphere atmo;       /* psi_key_atmosphere's: the bytes psi_cache_get compares */
} psi_disk_key;

static void make_key(psi_disk_key *k, const model_atmosphere *key, int sqrt_dirs, int steps, size_t bytes)
{
    memset(k, 0, sizeof *k);
    memcpy(k->magic, "vkskyPsi", 8);
    k->version = PSI_DISK_VERSION;
    k->table_bytes = (uint32_t)bytes;
    k->sqrt_dirs = sqrt_dirs, k->steps = steps;
    k->atmo = *key;
}

/* DIR/psi-<hash of the key>.bin into path; false if it does not fit. */
static bool file_name(char *path, size_t size, const char *dir, const psi_disk_key *k)
{
    int n = snprintf(path, size, "%s/psi-%016llx.bin", dir,
                     (unsigned long long)model_fnv1a(MODEL_FNV1A_OFFSET, k, sizeof *k));
    return n > 0 && (size_t)n < size;
}

void *psi_disk_load(const char *dir, const model_atmosphere *key_atmosphere, int sqrt_dirs, int steps, size_t bytes)
{
    psi_disk_key key, stored;
    make_key(&key, key_atmosphere, sqrt_dirs, steps, bytes);
    char path[4096];
    if (!file_name(path, sizeof path, dir, &key)) return NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    void *t = malloc(bytes);
    uint64_t sum = 0;
    char extra;
    bool ok = t && fread(&stored, sizeof stored, 1, f) == 1 && fread(t, bytes, 1, f) == 1 &&
              fread(&sum, sizeof sum, 1, f) == 1 && fread(&extra, 1, 1, f) == 0 &&
              memcmp(&stored, &key, sizeof key) == 0 &&
              sum == model_fnv1a(model_fnv1a(MODEL_FNV1A_OFFSET, &stored, sizeof stored), t, bytes);
    fclose(f);
    if (!ok) {
        free(t);
        return NULL;
    }
    return t;
}

void psi_disk_store(const char *dir, const model_atmosphere *key_atmosphere, int sqrt_dirs, int steps,
                    const void *t, size_t bytes)
{
    psi_disk_key key;
    make_key(&key, key_atmosphere, sqrt_dirs, steps, bytes);
    char path[4096], tmp[4200];
    if (!file_name(path, sizeof path, dir, &key) ||
        snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid()) >= (int)sizeof tmp)
        return;
    uint64_t sum = model_fnv1a(model_fnv1a(MODEL_FNV1A_OFFSET, &key, sizeof key), t, bytes);
    FILE *f = fopen(tmp, "wb");
    if (!f) return;   /* an unwritable directory: the table stays this process's */
    bool ok = fwrite(&key, sizeof key, 1, f) == 1 && fwrite(t, bytes, 1, f) == 1 && fwrite(&sum, sizeof sum, 1, f) == 1;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path) != 0) remove(tmp);
}
