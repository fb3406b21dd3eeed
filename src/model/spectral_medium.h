/* The medium per wavelength (issue 32): what the model's RGB medium (medium.h) becomes when colour comes from the
 * spectrum. Each coefficient of each species is a law of the wavelength:
 *   - rgb:       the three RGB values at 680, 550 and 440 nm (the wavelengths the RGB coefficients stand for, as in
 *                Bruneton's demo), linear in wavelength between them and held beyond them;
 *   - rayleigh:  scale x N_s x sigma(lambda), sigma the Rayleigh cross section of dry air of Bodhaine et al. 1999
 *                (J. Atmos. Oceanic Technol. 16, 1854-1861: Peck & Reeves refractive index with 360 ppm CO2, the
 *                lambda^-4 law, the King depolarisation factor of N2, O2, Ar, CO2), N_s = 2.546899e25 m^-3 (288.15 K,
 *                1013.25 hPa); scale 1 is sea-level air of that state;
 *   - angstrom:  value_550 x (lambda / 550 nm)^-exponent (aerosols: Angstrom's law);
 *   - ozone:     number density (m^-3, at density 1) x the ozone absorption cross section (model/spectrum.h).
 * A coefficient is 1/km at density 1 (the density profiles stay those of model_atmosphere).
 *
 * Plain C, no integrators. The CPU reference packs three wavelengths into the three channels of a
 * model_atmosphere (spectral_medium_pack); a GPU packing four wavelengths to a texel calls spectral_medium_eval for
 * each of the four and stores the scalars side by side. */
#ifndef VKSKY_MODEL_SPECTRAL_MEDIUM_H
#define VKSKY_MODEL_SPECTRAL_MEDIUM_H

#include "model/medium.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The wavelengths an RGB coefficient triple stands for (scene.h: "[r, g, b] = three numbers for 680, 550, 440"). */
#define SPECTRAL_NM_RED 680.0
#define SPECTRAL_NM_GREEN 550.0
#define SPECTRAL_NM_BLUE 440.0
/* Bodhaine et al. 1999: molecules per m^3 of air at 288.15 K and 1013.25 hPa. */
#define SPECTRAL_AIR_NUMBER_DENSITY 2.546899e25

typedef enum spectral_law_kind {
    SPECTRAL_LAW_RGB = 0,
    SPECTRAL_LAW_RAYLEIGH,
    SPECTRAL_LAW_ANGSTROM,
    SPECTRAL_LAW_OZONE,
} spectral_law_kind;

typedef struct spectral_law {
    spectral_law_kind kind;
    double rgb[3];   /* RGB: /km at 680, 550, 440 nm */
    double scale;    /* RAYLEIGH: multiple of sea-level air; OZONE: number density at density 1, m^-3 */
    double value_550, exponent; /* ANGSTROM: /km at 550 nm, Angstrom exponent */
} spectral_law;

typedef struct spectral_medium {
    spectral_law rayleigh_scattering, mie_scattering, mie_absorption, ozone_absorption;
    spectral_law extra_scattering[MODEL_MAX_EXTRA_SPECIES], extra_absorption[MODEL_MAX_EXTRA_SPECIES];
} spectral_medium;

/* The coefficients at one wavelength, 1/km at density 1 (what a GPU texel channel holds). */
typedef struct spectral_coefficients {
    double rayleigh_scattering, mie_scattering, mie_absorption, ozone_absorption;
    double extra_scattering[MODEL_MAX_EXTRA_SPECIES], extra_absorption[MODEL_MAX_EXTRA_SPECIES];
} spectral_coefficients;

/* Bodhaine et al. 1999 eqs. (2), (4), (17), (23): the Rayleigh scattering cross section of dry air with 360 ppm
 * CO2, m^2 per molecule, and its King factor alone. */
double spectral_rayleigh_cross_section(double nm);
double spectral_king_factor(double nm);

/* A law's value at nm (/km at density 1; never negative). */
double spectral_law_eval(const spectral_law *l, double nm);

/* The spectral medium the model's RGB medium stands for: Rayleigh the Bodhaine law scaled to the green value,
 * Mie an Angstrom law through the red and blue values scaled to the green one, ozone the cross sections scaled to
 * the green value; a species whose red and blue values do not follow that shape within 10 % (Rayleigh; ozone 25 %)
 * keeps the RGB law, as do the extra species. Hillaire's Earth (Bruneton's coefficients, which are these laws at
 * 680/550/440 nm) maps to the physical laws. */
void spectral_medium_from_rgb(const model_atmosphere *a, spectral_medium *out);

void spectral_medium_eval(const spectral_medium *m, double nm, spectral_coefficients *out);

/* *out = *base with its three channels' coefficients those of the wavelengths nm[0..2] and its sun illuminance
 * sun[0..2] (the density profiles, radii, phase and sun geometry are base's). */
void spectral_medium_pack(const spectral_medium *m, const model_atmosphere *base, const double nm[3],
                          const double sun[3], model_atmosphere *out);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_MODEL_SPECTRAL_MEDIUM_H */
