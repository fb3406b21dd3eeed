/* --spectral N on the GPU (issue 32 item 4): what the command line decides about it, before any GPU work (which
 * outputs can be rendered spectral, three or four wavelengths a pass, --quality auto's and --max-color-error's pick),
 * and the host's tone map of the sum. The groups themselves (each group's wavelengths packed into the colour channels
 * of a scene, the CPU reference's packing, reference/spectral.h: same bins, same medium per wavelength, same CIE
 * weights; the sum through the bins' exact XYZ weights into linear Rec.709) are rendered through include/vksky.h by
 * app/runs/spectral_host.c (docs/spectral.md, "The GPU's --spectral N"). No src/sky or src/lib header
 * (tests/layering_test.sh). */
#ifndef VKSKY_APP_SPECTRAL_RENDER_H
#define VKSKY_APP_SPECTRAL_RENDER_H
#include "app/cli/options_struct.h"

#define SPECTRAL_GPU_MAX 48   /* 16 groups: the largest count the GPU path accepts */

/* Bad combinations of --spectral with the GPU's outputs (the window, --bench, a sequence in several bands):
 * one line on stderr naming `flag` (the flag that asked for the wavelengths) and 2; else 0. Call before any GPU work. */
int spectral_render_check(const options *o, const char *flag);
/* Why o's outputs cannot be rendered spectral (a phrase for a message), or NULL: they can. EXR and PNG stills and
 * sequences can, EXR and PNG environment maps and banded images can (a pass per group in every band); the window,
 * --bench and a sequence in several bands cannot. */
const char *spectral_render_unable(const options *o);

/* Whether --spectral renders four wavelengths to a texel (the SPECTRAL4 build) rather than three (the RGB shaders,
 * one group per three channels): four unless the horizon passes within 3 pixels of the frame (the four-wide image
 * has no horizon resolve); VKSKY_SPECTRAL_PACK=3 or 4 forces one (to check one against the other). */
bool spectral_render_four_wide(const options *o);

/* --max-color-error: the fewest wavelengths (0: RGB) whose measured worst CIEDE2000 against the 48-wavelength spectral
 * reference is <= max_de on every scene class of the set (quality.h's classes; app/quality/quality_color_table.h,
 * from tools/color_error's 57 rows). -1 if none is; *measured gets the pick's worst (or the best setting's worst). */
int spectral_pick(double max_de, unsigned classes, double *measured);

/* --quality auto's colour (issue 32): where RGB's measured worst CIEDE2000 on the run's scene classes (a sequence:
 * every frame's, one choice for the run) is over the default colour budget SPECTRAL_AUTO_BUDGET, the fewest
 * wavelengths within it (spectral_pick), said on one stdout line. On a CPU device (o->quality_cpu_device, the device
 * kind auto's quality tables were chosen by) only where RGB is over SPECTRAL_AUTO_RGB_KEEP_CPU: there a spectral still
 * costs 2.0-3.4x an RGB one (lavapipe), on a GPU 1.03-1.11x (H200; docs/spectral.md "Auto by the device's kind").
 * A run the spectral path cannot render (`impossible`: the caller's reason, e.g. a composite; spectral_render_unable's;
 * --bench) keeps RGB and says why on stdout; the window keeps RGB silently (interactive). Not with a colour choice of
 * its own (--spectral, --max-color-error). Sets o->spectral; returns it (0: RGB kept). */
#define SPECTRAL_AUTO_BUDGET 1.0
#define SPECTRAL_AUTO_RGB_KEEP_CPU 3.0
int spectral_auto(options *o, const char *impossible);

/* The spectral sum's PNG (docs/spectral.md, "The PNG"): rgb (RGBA floats, linear Rec.709 in the HDR image's units)
 * tone-mapped into display (RGBA8 sRGB) by the GPU tone map's law without bloom or dither, at v's exposure or, under
 * v->auto_exposure, at the exposure metered on the host. A host of include/vksky.h calls these
 * (app/runs/spectral_host.c). */
typedef struct spectral_meter {
    double log_sum, count;   /* sum of ln max(Y, 1e-4) in cd/m2 (or relative units), and the pixels counted */
} spectral_meter;
/* Adds rows first_row .. first_row + rows - 1 of a w x whole_h image of v's projection (rgb: those rows) to the
 * meter, in row order (bands metered in order sum what the whole image's meter sums). every_pixel: whether the ground's
 * pixels count too (a lit ground); bottom_radius: the planet's (km). */
void spectral_render_meter_rows(const sky_view *v, int w, int whole_h, int first_row, int rows, bool every_pixel,
                                double bottom_radius, const float *rgb, spectral_meter *m);
/* The exposure to tone-map with: v's, or under v->auto_exposure the meter's (one stderr line unless quiet; bands: how
 * many the meter saw). */
double spectral_render_exposure(const sky_view *v, const spectral_meter *m, int bands, bool quiet);
/* rows x w pixels of rgb into display at exposure_ev (v's units and operator), dithered as the GPU's tone map dithers
 * (unless v->no_dither): the rows' first is row first_row of the whole image (a band's, pad rows included). */
void spectral_render_tonemap_rows(const sky_view *v, double exposure_ev, int w, int rows, int first_row,
                                  const float *rgb, void *display);

#endif
