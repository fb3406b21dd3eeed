/* tests/test_psi_threads.c: the reference's Psi table is the same bytes however many threads fill its rows
 * (src/reference/psi_table.c: rows on worker threads, issue 27 items 3 and 5). Each table is compared with memcmp
 * against the one filled on this thread alone, for the atmospheres that take different paths through the row
 * (the penumbra model with the second bounce's moments, the lesson's fade without them, a layered medium), and for
 * thread counts that divide the 24 rows and that do not, more threads than cores, and the default (0).
 * Small Psi counts keep it quick: a row's result depends on its own inputs only, whatever the counts.
 * Then the tables on disk (psi_disk.c, VKSKY_PSI_CACHE: the suite's, issue 27 item 5): psi_cache_get stores what it
 * builds and loads it back in a later process (here: after psi_cache_clear) as the same bytes, trusts a good file of
 * its key (a file holding another table under this key is what it returns: the disk is really read), and ignores a
 * corrupt, truncated or longer file, a file of another key, and a directory it cannot write. */
#include "reference/ref_internal.h"
#include "check.h"
#include "test_atmospheres.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The one psi-*.bin file in dir (its path into path), or false. */
static bool only_file(const char *dir, char *path, size_t size)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (!strncmp(e->d_name, "psi-", 4) && ++n == 1) snprintf(path, size, "%s/%s", dir, e->d_name);
    if (d) closedir(d);
    return n == 1;
}

/* Flip one byte at offset (from the end when negative), or cut the file to keep bytes. */
static void damage(const char *path, long offset, long keep)
{
    FILE *f = fopen(path, "r+b");
    if (!f) return;
    if (keep >= 0) {
        CHECK(truncate(path, keep) == 0, "truncate %s", path);
    } else {
        fseek(f, offset, offset < 0 ? SEEK_END : SEEK_SET);
        int c = fgetc(f);
        fseek(f, -1, SEEK_CUR);
        fputc(c ^ 0x5a, f);
    }
    fclose(f);
}

static void disk_cache(const model_atmosphere *earth, const model_atmosphere *other)
{
    char dir[] = "/tmp/vksky_psi_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return;
    }
    setenv("VKSKY_PSI_CACHE", dir, 1);
    const size_t bytes = psi_table_bytes();
    model_atmosphere key;   /* the atmosphere as psi_cache_get keys its tables */
    psi_key_atmosphere(earth, &key);
    psi_table *want = psi_table_build(earth, 8, 16, 0), *theirs = psi_table_build(other, 8, 16, 0);
    char path[4096];
    psi_cache_clear();
    const psi_table *t = psi_cache_get(earth, 8, 16);
    CHECK(t && memcmp(t, want, bytes) == 0, "disk: the built table differs from psi_table_build's");
    CHECK(only_file(dir, path, sizeof path), "disk: no single psi-*.bin file stored in %s", dir);
    psi_cache_clear();
    t = psi_cache_get(earth, 8, 16);
    CHECK(t && memcmp(t, want, bytes) == 0, "disk: the loaded table differs from the built one");
    /* Another table under this key: what a load returns, so the file is what psi_cache_get read. */
    psi_disk_store(dir, &key, 8, 16, theirs, bytes);
    psi_cache_clear();
    t = psi_cache_get(earth, 8, 16);
    CHECK(t && memcmp(t, theirs, bytes) == 0, "disk: psi_cache_get did not read the file");
    /* Bad files: ignored (NULL from the loader), the table built again as psi_table_build's and the file made good. */
    struct { const char *what; long offset, keep; } bad[] = {
        {"a byte of the key", 20, -1}, {"a byte of the table", 4096, -1}, {"a byte of the checksum", -2, -1},
        {"truncated", 0, 1000}, {"empty", 0, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        psi_disk_store(dir, &key, 8, 16, want, bytes);
        damage(path, bad[i].offset, bad[i].keep);
        psi_table *l = psi_disk_load(dir, &key, 8, 16, bytes);
        CHECK(l == NULL, "disk: %s: the file was loaded", bad[i].what);
        free(l);
        psi_cache_clear();
        t = psi_cache_get(earth, 8, 16);
        CHECK(t && memcmp(t, want, bytes) == 0, "disk: %s: the table differs from psi_table_build's", bad[i].what);
        l = psi_disk_load(dir, &key, 8, 16, bytes);
        CHECK(l && memcmp(l, want, bytes) == 0, "disk: %s: the file was not stored again", bad[i].what);
        free(l);
    }
    FILE *f = fopen(path, "ab");   /* a byte past the end */
    if (f) fputc(0, f), fclose(f);
    psi_table *l = psi_disk_load(dir, &key, 8, 16, bytes);
    CHECK(l == NULL, "disk: a longer file was loaded");
    free(l);
    l = psi_disk_load(dir, &key, 8, 32, bytes);   /* other counts: another key */
    CHECK(l == NULL, "disk: a table of other counts was loaded");
    free(l);
    /* An unwritable directory (a file where it should be): built, nothing stored, no failure. */
    remove(path);
    char file_dir[4200];
    snprintf(file_dir, sizeof file_dir, "%s/not_a_dir", dir);
    f = fopen(file_dir, "w");
    if (f) fclose(f);
    setenv("VKSKY_PSI_CACHE", file_dir, 1);
    psi_cache_clear();
    t = psi_cache_get(earth, 8, 16);
    CHECK(t && memcmp(t, want, bytes) == 0, "disk: unwritable: the table differs from psi_table_build's");
    remove(file_dir);
    rmdir(dir);
    unsetenv("VKSKY_PSI_CACHE");
    psi_cache_clear();
    free(want), free(theirs);
}

int main(void)
{
    model_atmosphere atmos[3];
    model_atmosphere_earth(&atmos[0]);
    atmos[1] = atmos[0];
    atmos[1].sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
    atmos[2] = test_layered_atmosphere();
    const char *names[3] = {"earth (penumbra)", "earth (lesson fade)", "layered"};
    const int counts[] = {2, 3, 5, 7, 24, 64, 0};
    const size_t bytes = psi_table_bytes();
    psi_table *first = NULL;
    for (int i = 0; i < 3; ++i) {
        psi_table *one = psi_table_build(&atmos[i], 8, 16, 1);
        CHECK(one != NULL, "%s: one thread: no table", names[i]);
        if (!one) continue;
        /* the table holds numbers (log Psi, moments), all finite: a garbage table would not compare equal anyway */
        const double *v = (const double *)one;
        int finite = 1;
        for (size_t k = 0; k < bytes / sizeof *v; ++k) finite = finite && isfinite(v[k]);
        CHECK(finite, "%s: a non-finite entry", names[i]);
        /* different media give different tables (the comparison below can tell tables apart) */
        if (first) CHECK(memcmp(first, one, bytes) != 0, "%s: the same table as %s", names[i], names[0]);
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; ++c) {
            psi_table *many = psi_table_build(&atmos[i], 8, 16, counts[c]);
            CHECK(many && memcmp(one, many, bytes) == 0, "%s: %d threads: the table differs from one thread's",
                  names[i], counts[c]);
            free(many);
        }
        if (!first) first = one;
        else free(one);
    }
    free(first);
    disk_cache(&atmos[0], &atmos[2]);
    return check_report("psi_threads");
}
