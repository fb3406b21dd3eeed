/* The medium per wavelength (spectral_medium.h): the laws and the RGB medium's spectral counterpart. */
#include "model/spectral_medium.h"
#include "model/spectrum.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Bodhaine et al. 1999: CO2 360 ppm (their standard), in parts per volume and in percent. */
static const double CO2_PPV = 360e-6;

double spectral_king_factor(double nm)
{
    double l = nm * 1e-3, il2 = 1.0 / (l * l); /* micrometres */
    double f_n2 = 1.034 + 3.17e-4 * il2;                       /* eq. (5), Bates 1984 */
    double f_o2 = 1.096 + 1.385e-3 * il2 + 1.448e-4 * il2 * il2; /* eq. (6) */
    double c = CO2_PPV * 100.0;                                /* percent */
    /* eq. (23): the volume-weighted mean of N2, O2, Ar (1.00) and CO2 (1.15). */
    return (78.084 * f_n2 + 20.946 * f_o2 + 0.934 * 1.00 + c * 1.15) / (78.084 + 20.946 + 0.934 + c);
}

double spectral_rayleigh_cross_section(double nm)
{
    double l = nm * 1e-3, il2 = 1.0 / (l * l);
    /* eq. (4), Peck & Reeves 1972 for 300 ppm CO2, then eq. (17) for the CO2 content. */
    double n300 = 1e-8 * (8060.51 + 2480990.0 / (132.274 - il2) + 17455.7 / (39.32957 - il2));
    double nm1 = n300 * (1.0 + 0.54 * (CO2_PPV - 0.0003));
    double n2 = (1.0 + nm1) * (1.0 + nm1);
    double lcm = nm * 1e-7, Ns = SPECTRAL_AIR_NUMBER_DENSITY * 1e-6; /* cm, cm^-3 */
    /* eq. (2): sigma = 24 pi^3 (n^2 - 1)^2 / (lambda^4 Ns^2 (n^2 + 2)^2) F_air, in cm^2. */
    double sigma = 24.0 * PI * PI * PI * (n2 - 1.0) * (n2 - 1.0) /
                   (lcm * lcm * lcm * lcm * Ns * Ns * (n2 + 2.0) * (n2 + 2.0)) * spectral_king_factor(nm);
    return sigma * 1e-4;
}

double spectral_law_eval(const spectral_law *l, double nm)
{
    double v = 0.0;
    switch (l->kind) {
    case SPECTRAL_LAW_RAYLEIGH:
        v = l->scale * SPECTRAL_AIR_NUMBER_DENSITY * spectral_rayleigh_cross_section(nm) * 1e3;
        break;
    case SPECTRAL_LAW_ANGSTROM:
        v = l->value_550 * pow(nm / SPECTRAL_NM_GREEN, -l->exponent);
        break;
    case SPECTRAL_LAW_OZONE:
        v = l->scale * spectrum_ozone_cross_section(nm) * 1e3;
        break;
    case SPECTRAL_LAW_RGB:
    default:
        /* rgb[] is ordered red, green, blue: descending wavelength. */
        if (nm >= SPECTRAL_NM_RED)
            v = l->rgb[0];
        else if (nm >= SPECTRAL_NM_GREEN)
            v = l->rgb[1] + (l->rgb[0] - l->rgb[1]) * (nm - SPECTRAL_NM_GREEN) / (SPECTRAL_NM_RED - SPECTRAL_NM_GREEN);
        else if (nm >= SPECTRAL_NM_BLUE)
            v = l->rgb[2] + (l->rgb[1] - l->rgb[2]) * (nm - SPECTRAL_NM_BLUE) / (SPECTRAL_NM_GREEN - SPECTRAL_NM_BLUE);
        else
            v = l->rgb[2];
        break;
    }
    return v > 0.0 && isfinite(v) ? v : 0.0;
}

static spectral_law rgb_law(const double rgb[3])
{
    spectral_law l = {.kind = SPECTRAL_LAW_RGB};
    memcpy(l.rgb, rgb, sizeof l.rgb);
    return l;
}

/* True if the law, scaled to rgb's green value, meets the red and blue values within `tol` (relative). */
static bool follows(const spectral_law *l, const double rgb[3], double tol)
{
    for (int c = 0; c < 3; c += 2) {
        double nm = c == 0 ? SPECTRAL_NM_RED : SPECTRAL_NM_BLUE, want = rgb[c], got = spectral_law_eval(l, nm);
        if (!(fabs(got - want) <= tol * want))
            return false;
    }
    return true;
}

/* An Angstrom law through the red and blue values, scaled to the green one (the RGB law when one is not > 0). */
static spectral_law angstrom_law(const double rgb[3])
{
    if (!(rgb[0] > 0.0 && rgb[1] > 0.0 && rgb[2] > 0.0))
        return rgb_law(rgb);
    double alpha = -log(rgb[0] / rgb[2]) / log(SPECTRAL_NM_RED / SPECTRAL_NM_BLUE);
    return (spectral_law){.kind = SPECTRAL_LAW_ANGSTROM, .value_550 = rgb[1], .exponent = alpha};
}

void spectral_medium_from_rgb(const model_atmosphere *a, spectral_medium *out)
{
    memset(out, 0, sizeof *out);
    const double *r = a->rayleigh_scattering;
    spectral_law ray = {.kind = SPECTRAL_LAW_RAYLEIGH};
    ray.scale = r[1] / (SPECTRAL_AIR_NUMBER_DENSITY * spectral_rayleigh_cross_section(SPECTRAL_NM_GREEN) * 1e3);
    out->rayleigh_scattering = r[1] > 0.0 && follows(&ray, r, 0.1) ? ray : rgb_law(r);

    out->mie_scattering = angstrom_law(a->mie_scattering);
    out->mie_absorption = angstrom_law(a->mie_absorption);

    const double *o = a->ozone_absorption;
    spectral_law oz = {.kind = SPECTRAL_LAW_OZONE};
    double s550 = spectrum_ozone_cross_section(SPECTRAL_NM_GREEN);
    oz.scale = s550 > 0.0 ? o[1] / (s550 * 1e3) : 0.0;
    /* 25 %: Hillaire's red ozone value is 16 % below what these binned cross sections give at 680 nm. */
    out->ozone_absorption = o[1] > 0.0 && follows(&oz, o, 0.25) ? oz : rgb_law(o);

    for (int i = 0; i < a->extra_count && i < MODEL_MAX_EXTRA_SPECIES; ++i) {
        out->extra_scattering[i] = rgb_law(a->extra[i].scattering);
        out->extra_absorption[i] = rgb_law(a->extra[i].absorption);
    }
}

void spectral_medium_eval(const spectral_medium *m, double nm, spectral_coefficients *out)
{
    out->rayleigh_scattering = spectral_law_eval(&m->rayleigh_scattering, nm);
    out->mie_scattering = spectral_law_eval(&m->mie_scattering, nm);
    out->mie_absorption = spectral_law_eval(&m->mie_absorption, nm);
    out->ozone_absorption = spectral_law_eval(&m->ozone_absorption, nm);
    for (int i = 0; i < MODEL_MAX_EXTRA_SPECIES; ++i) {
        out->extra_scattering[i] = spectral_law_eval(&m->extra_scattering[i], nm);
        out->extra_absorption[i] = spectral_law_eval(&m->extra_absorption[i], nm);
    }
}

void spectral_medium_pack(const spectral_medium *m, const model_atmosphere *base, const double nm[3],
                          const double sun[3], model_atmosphere *out)
{
    *out = *base;
    for (int c = 0; c < 3; ++c) {
        spectral_coefficients k;
        spectral_medium_eval(m, nm[c], &k);
        out->rayleigh_scattering[c] = k.rayleigh_scattering;
        out->mie_scattering[c] = k.mie_scattering;
        out->mie_absorption[c] = k.mie_absorption;
        out->ozone_absorption[c] = k.ozone_absorption;
        for (int i = 0; i < base->extra_count && i < MODEL_MAX_EXTRA_SPECIES; ++i) {
            out->extra[i].scattering[c] = k.extra_scattering[i];
            out->extra[i].absorption[c] = k.extra_absorption[i];
        }
        out->sun_illuminance[c] = sun[c];
    }
}
