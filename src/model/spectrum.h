/* Spectral data for physical light: the sun's spectrum at the top of the atmosphere, the CIE 1931 2-degree colour
 * matching functions, ozone's absorption cross sections, and the step from XYZ to linear Rec.709. Sources, licences
 * and how the tables were binned: docs/data_sources.md (and the comments in spectrum.c). Every function takes a
 * wavelength in nanometres; outside [SPECTRUM_NM_MIN, SPECTRUM_NM_MAX] it returns 0 (the tables say nothing there). */
#ifndef VKSKY_MODEL_SPECTRUM_H
#define VKSKY_MODEL_SPECTRUM_H

#define SPECTRUM_NM_MIN 360.0
#define SPECTRUM_NM_MAX 830.0
#define SPECTRUM_LUMINOUS_EFFICACY 683.0            /* lm/W: the SI definition of the candela (540 THz) */

double spectrum_solar_irradiance(double nm);       /* W m^-2 nm^-1 at the top of the atmosphere (interpolated) */
void   spectrum_cie1931(double nm, double xyz[3]); /* xbar, ybar, zbar (interpolated) */
double spectrum_ozone_cross_section(double nm);    /* m^2 per molecule */
void   spectrum_xyz_to_rec709(const double xyz[3], double rgb[3]); /* linear Rec.709 / sRGB primaries, D65 */
double spectrum_solar_illuminance_toa(void);       /* lx: 683 * integral of E(lambda) ybar(lambda) d lambda (~1.3e5) */

/* The sun at the top of the atmosphere as linear Rec.709 whose Y (0.2126 R + 0.7152 G + 0.0722 B) is its
 * illuminance in lux: 683 * integral of E(lambda) (xbar, ybar, zbar) d lambda, through spectrum_xyz_to_rec709. */
void   spectrum_solar_rec709_toa(double rgb[3]);

#endif
