/* tests/test_psi_threads.c: the reference's Psi table is the same bytes however many threads fill its rows
 * (src/reference/psi_table.c: rows on worker threads, issue 27 items 3 and 5). Each table is compared with memcmp
 * against the one filled on this thread alone, for the atmospheres that take different paths through the row
 * (the penumbra model with the second bounce's moments, the lesson's fade without them, a layered medium), and for
 * thread counts that divide the 24 rows and that do not, more threads than cores, and the default (0).
 * Small Psi counts keep it quick: a row's result depends on its own inputs only, whatever the counts. */
#include "reference/ref_internal.h"
#include "check.h"
#include "test_atmospheres.h"

#include <stdlib.h>
#include <string.h>

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
    return check_report("psi_threads");
}
