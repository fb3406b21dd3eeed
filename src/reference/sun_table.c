/* The pieces both the Psi quadrature (multiscatter.c) and the Psi table (psi_table.c) use: the bicubic
 * (Catmull-Rom) taps, the sun transmittance table (only for filling the Psi table fast) and the cancellation flag a
 * table build looks at between rows. Kept apart so that the calls between the two go one way only
 * (psi_table -> multiscatter -> sun_table). */
#include "reference/ref_internal.h"

#include <math.h>
#include <stdlib.h>

void cubic_taps(double f, int n, int mirror_lo, int mirror_hi, int idx[4], double w[4])
{
    if (n < 2) {
        idx[0] = idx[1] = idx[2] = idx[3] = 0;
        w[0] = 1.0;
        w[1] = w[2] = w[3] = 0.0;
        return;
    }
    f = clampd(f, 0.0, n - 1.0);
    int i = (int)f;
    if (i > n - 2)
        i = n - 2;
    double cw[4];
    catmull_rom(f - i, cw);
    for (int k = 0; k < 4; ++k)
        w[k] = 0.0;
    for (int k = 0; k < 4; ++k) {
        int j = i - 1 + k;
        if (j < 0) { /* k == 0, i == 0: node 0 is slot 1, node 1 slot 2 */
            if (mirror_lo) {
                w[2] += cw[k];
            } else {
                w[1] += 2.0 * cw[k];
                w[2] -= cw[k];
            }
        } else if (j > n - 1) { /* k == 3, i == n - 2: node n-1 is slot 2, node n-2 slot 1 */
            if (mirror_hi) {
                w[1] += cw[k];
            } else {
                w[2] += 2.0 * cw[k];
                w[1] -= cw[k];
            }
        } else {
            w[k] += cw[k];
        }
    }
    for (int k = 0; k < 4; ++k) {
        int j = i - 1 + k;
        idx[k] = j < 0 ? 0 : (j > n - 1 ? n - 1 : j);
    }
}

/* ref_set_cancel: the flag a table build looks at between rows. */
static const volatile sig_atomic_t *g_cancel;

void ref_set_cancel(const volatile sig_atomic_t *flag)
{
    g_cancel = flag;
}

int ref_cancelled(void)
{
    return g_cancel && *g_cancel;
}

sun_table *sun_table_build(const model_atmosphere *a)
{
    sun_table *t = malloc(sizeof *t);
    if (!t)
        return NULL;
    for (int j = 0; j < SUN_TABLE_NY; ++j) {
        if (ref_cancelled()) {
            free(t);
            return NULL;
        }
        for (int i = 0; i < SUN_TABLE_NX; ++i) {
            double h, mu, tau[3];
            bruneton_params(a, (double)i / (SUN_TABLE_NX - 1), (double)j / (SUN_TABLE_NY - 1), &h, &mu);
            optical_depth(a, h, mu, SUN_TABLE_STEPS, tau);
            for (int c = 0; c < 3; ++c)
                t->T[j][i][c] = exp(-tau[c]);
        }
    }
    return t;
}

void sun_table_eval(const sun_table *t, const model_atmosphere *a, double h, double mu, double T[3])
{
    double x_mu, x_r, wx[4], wy[4];
    int ix[4], iy[4];
    bruneton_x(a, h, mu, &x_mu, &x_r);
    cubic_taps(x_mu * (SUN_TABLE_NX - 1), SUN_TABLE_NX, 0, 0, ix, wx);
    cubic_taps(x_r * (SUN_TABLE_NY - 1), SUN_TABLE_NY, 0, 0, iy, wy);
    for (int c = 0; c < 3; ++c) {
        double v = 0.0;
        for (int b = 0; b < 4; ++b)
            for (int k = 0; k < 4; ++k)
                v += wy[b] * wx[k] * t->T[iy[b]][ix[k]][c];
        T[c] = clampd(v, 0.0, 1.0);
    }
}
