/* src/model/spectrum.c against known answers that do not come from the program:
 *  1. the transcription: the sum of the 48 solar bins and of the 95 CMF rows, summed from the transcription source
 *     (Bruneton's demo.cc / constants.h, with awk) -- a typo in a digit moves them;
 *  2. the CIE 1931 2-degree functions' published integrals over 360-830 nm (CVRL's 1 nm table: xbar 106.865,
 *     ybar 106.857, zbar 106.892; the 5 nm table's trapezoid rule agrees to 0.01 %), ybar(555) = 1, and the
 *     equal-energy white E at x = y = 1/3;
 *  3. the XYZ -> Rec.709 matrix: IEC 61966-2-1's printed matrix (4 decimals), D65 (x 0.3127, y 0.3290, Y 1) -> 1,1,1,
 *     and the luminance row of its inverse = BT.709's 0.2126 0.7152 0.0722;
 *  4. the sun at the top of the atmosphere: illuminance among the published luminous solar constants, 127.5-128 klx
 *     in older tables (IES, CIE) to 133.3 klx (Darula, Kittler & Gueymard 2005, Solar Energy 79(5), from modern
 *     extraterrestrial spectra such as the one ASTM G-173 carries): 1.27-1.34e5 lx; its Rec.709 Y is that
 *     illuminance; the interpolated irradiance integrates to the bins' sum;
 *  5. ozone's Chappuis band: the maximum near 600 nm, ~5e-25 m^2 (Serdyuchenko 2014: 5.2e-21 cm^2 at 603 nm);
 *  6. zero outside 360-830 nm. */
#include "model/spectrum.h"
#include <math.h>
#include <stdio.h>
#include "check.h"

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

/* Trapezoid rule at 1 nm over [360, 830] of component c of the CMFs (c 0..2) weighted by the sun (sun != 0). */
static double integrate(int c, int sun)
{
    double s = 0.0;
    for (int nm = 360; nm <= 830; ++nm) {
        double xyz[3];
        spectrum_cie1931(nm, xyz);
        double v = (c < 3 ? xyz[c] : 1.0) * (sun ? spectrum_solar_irradiance(nm) : 1.0);
        s += (nm == 360 || nm == 830) ? 0.5 * v : v;
    }
    return s;
}

int main(void)
{
    /* 1. transcription */
    double bins = 0.0;
    for (int i = 0; i < 47; ++i) /* bin centres 365..825 hit the table entries exactly; the 48th centre is 835 */
        bins += spectrum_solar_irradiance(365.0 + 10.0 * i);
    double last = (spectrum_solar_irradiance(830.0) - 0.5 * spectrum_solar_irradiance(825.0)) / 0.5; /* 835's value */
    bins += last;
    CHECK(fabs(bins - 74.54419) < 1e-9, "solar bins sum %.9f, source 74.54419", bins);
    double cs[3] = {0, 0, 0};
    for (int nm = 360; nm <= 830; nm += 5) {
        double xyz[3];
        spectrum_cie1931(nm, xyz);
        for (int c = 0; c < 3; ++c)
            cs[c] += xyz[c];
    }
    CHECK(fabs(cs[0] - 21.373139989) < 1e-8 && fabs(cs[1] - 21.371407850) < 1e-8 && fabs(cs[2] - 21.378664309) < 1e-8,
          "CMF column sums %.9f %.9f %.9f, source 21.373139989 21.371407850 21.378664309", cs[0], cs[1], cs[2]);

    /* 2. CMF integrals */
    double ix = integrate(0, 0), iy = integrate(1, 0), iz = integrate(2, 0);
    printf("CMF integrals: %.4f %.4f %.4f (CVRL 1 nm: 106.865 106.857 106.892)\n", ix, iy, iz);
    CHECK(rel(ix, 106.865) < 1e-3 && rel(iy, 106.857) < 1e-3 && rel(iz, 106.892) < 1e-3, "CMF integrals");
    double p[3];
    spectrum_cie1931(555.0, p);
    CHECK(fabs(p[1] - 1.0) < 1e-12, "ybar(555) = %.6f", p[1]);
    spectrum_cie1931(557.5, p); /* halfway between two rows: the mean of both */
    CHECK(fabs(p[1] - 0.5 * (1.0 + 0.995)) < 1e-12, "ybar(557.5) = %.6f", p[1]);
    double sum = ix + iy + iz;
    CHECK(fabs(ix / sum - 1.0 / 3.0) < 1e-3 && fabs(iy / sum - 1.0 / 3.0) < 1e-3, "equal-energy white x %.5f y %.5f",
          ix / sum, iy / sum);

    /* 3. the matrix */
    static const double iec[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
    for (int c = 0; c < 3; ++c) {
        double e[3] = {c == 0, c == 1, c == 2}, col[3];
        spectrum_xyz_to_rec709(e, col);
        for (int r = 0; r < 3; ++r)
            CHECK(fabs(col[r] - iec[r][c]) < 5e-4, "matrix [%d][%d] %.5f, IEC %.4f", r, c, col[r], iec[r][c]);
    }
    double d65[3] = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290}, w[3];
    spectrum_xyz_to_rec709(d65, w);
    CHECK(fabs(w[0] - 1) < 1e-6 && fabs(w[1] - 1) < 1e-6 && fabs(w[2] - 1) < 1e-6, "D65 -> %.7f %.7f %.7f", w[0], w[1],
          w[2]);
    /* the luminance row: the Y of RGB = e_k is the k-th entry of the inverse's second row (Cramer's rule). */
    {
        double m[3][3]; /* columns: images of the XYZ unit vectors */
        for (int c = 0; c < 3; ++c) {
            double e[3] = {c == 0, c == 1, c == 2}, col[3];
            spectrum_xyz_to_rec709(e, col);
            for (int r = 0; r < 3; ++r)
                m[r][c] = col[r];
        }
        double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        /* second row of the inverse = cofactors of the second column, transposed */
        double yr = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
        double yg = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
        double yb = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
        printf("Rec.709 luminance row: %.5f %.5f %.5f (BT.709: 0.2126 0.7152 0.0722)\n", yr, yg, yb);
        CHECK(fabs(yr - 0.2126) < 1e-4 && fabs(yg - 0.7152) < 1e-4 && fabs(yb - 0.0722) < 1e-4, "luminance row");
    }

    /* 4. the sun */
    double ev = spectrum_solar_illuminance_toa();
    double ev_trap = SPECTRUM_LUMINOUS_EFFICACY * integrate(1, 1);
    printf("solar illuminance at the top of the atmosphere: %.1f lx (1 nm trapezoid %.1f lx)\n", ev, ev_trap);
    CHECK(ev > 1.27e5 && ev < 1.34e5, "solar illuminance %.0f lx outside 1.27-1.34e5", ev);
    CHECK(rel(ev, ev_trap) < 1e-4, "Simpson %.1f vs trapezoid %.1f", ev, ev_trap);
    double rgb[3];
    spectrum_solar_rec709_toa(rgb);
    double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    printf("sun at the top of the atmosphere, Rec.709: %.0f %.0f %.0f lx-weighted (Y %.0f)\n", rgb[0], rgb[1], rgb[2], y);
    CHECK(rel(y, ev) < 2e-4, "sun's Rec.709 Y %.1f vs illuminance %.1f", y, ev);
    CHECK(rgb[0] > 0 && rgb[2] > 0 && rgb[0] / rgb[1] > 0.9 && rgb[0] / rgb[1] < 1.2 && rgb[2] / rgb[1] > 0.85 &&
              rgb[2] / rgb[1] < 1.1, "the sun above the air is near white (a ~5800 K black body), got %.3f 1 %.3f",
          rgb[0] / rgb[1], rgb[2] / rgb[1]);
    double e_int = 0.0; /* the interpolant's integral over 370..830 against the bins it was made from */
    for (int nm = 370; nm < 830; ++nm)
        e_int += 0.5 * (spectrum_solar_irradiance(nm) + spectrum_solar_irradiance(nm + 1));
    double e_bins = 0.0;
    for (int i = 1; i < 47; ++i)
        e_bins += 10.0 * spectrum_solar_irradiance(365.0 + 10.0 * i);
    CHECK(rel(e_int, e_bins) < 5e-3, "irradiance 370-830 nm: interpolated %.2f, bins %.2f W/m^2", e_int, e_bins);

    /* 5. ozone */
    double best = 0.0, best_nm = 0.0;
    for (int nm = 360; nm <= 830; ++nm)
        if (spectrum_ozone_cross_section(nm) > best)
            best = spectrum_ozone_cross_section(nm), best_nm = nm;
    printf("ozone maximum %.3e m^2 at %.0f nm\n", best, best_nm);
    CHECK(best_nm >= 590 && best_nm <= 615 && best > 4.5e-25 && best < 5.5e-25, "Chappuis maximum");

    /* 6. outside */
    spectrum_cie1931(359.0, p);
    CHECK(p[0] == 0 && p[1] == 0 && p[2] == 0 && spectrum_solar_irradiance(831.0) == 0 &&
              spectrum_ozone_cross_section(300.0) == 0, "zero outside 360-830 nm");

    if (check_failures)
        printf("%d failure(s)\n", check_failures);
    else
        printf("spectrum: all checks passed\n");
    return check_failures ? 1 : 0;
}
