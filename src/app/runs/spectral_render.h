/* --spectral N on the GPU (issue 32 item 4): the renderer run once per group of three wavelengths, each group's
 * wavelengths packed into the three colour channels of a model_atmosphere (the CPU reference's packing,
 * reference/spectral.h: same bins, same medium per wavelength, same CIE weights), and the groups' scene-linear images
 * summed through the bins' exact XYZ weights into linear Rec.709 (docs/spectral.md, "The GPU's --spectral N"). */
#ifndef VKSKY_APP_SPECTRAL_RENDER_H
#define VKSKY_APP_SPECTRAL_RENDER_H
#include "app/cli/options_struct.h"
#include "app/runs/sequence.h"

#define SPECTRAL_GPU_MAX 48   /* 16 groups: the largest count the GPU path accepts */

/* Bad combinations of --spectral with the GPU's outputs (the window, --bench, a PNG environment map or banded image):
 * one line on stderr naming `flag` (the flag that asked for the wavelengths) and 2; else 0. Call before any GPU work. */
int spectral_render_check(const options *o, const char *flag);
/* Why o's outputs cannot be rendered spectral (a phrase for a message), or NULL: they can. EXR and PNG stills and
 * sequences can, EXR environment maps and banded images can (a pass per group in every band); the window, --bench
 * and PNG maps or banded images cannot. */
const char *spectral_render_unable(const options *o);

/* Whether --spectral renders four wavelengths to a texel (the SPECTRAL4 build) rather than three (the RGB shaders,
 * one group per three channels): four unless the horizon passes within 3 pixels of the frame (the four-wide image
 * has no horizon resolve); VKSKY_SPECTRAL_PACK=3 or 4 forces one (to check one against the other). */
bool spectral_render_four_wide(const options *o);

/* Arm the frame function for o's wavelengths and medium; inner renders (and reads back) one frame. */
void spectral_render_begin(const options *o, sequence_render_fn inner);
/* The plain inner frame: sky_renderer_render (a band of an environment map, app/runs/tiles.c). */
void spectral_render_plain(sky_renderer *r, const frame_desc *f);

/* A sequence_render_fn: the frame rendered once per wavelength group and combined into r->readback_linear; with a PNG
 * among the outputs, the sum tone-mapped on the host into r->readback_display (spectral_render_tonemap). The renderer is left holding the
 * last group's atmosphere; sequence_render sets the frame's own before the next frame. */
void spectral_render_frame(sky_renderer *r, const frame_desc *f);

/* --max-color-error: the fewest wavelengths (0: RGB) whose measured worst CIEDE2000 against the 48-wavelength spectral
 * reference is <= max_de on every scene class of the set (quality.h's classes; app/quality/quality_color_table.h,
 * from tools/color_error's 57 rows). -1 if none is; *measured gets the pick's worst (or the best setting's worst). */
int spectral_pick(double max_de, unsigned classes, double *measured);

/* --quality auto's colour (issue 32): where RGB's measured worst CIEDE2000 on the run's scene classes (a sequence:
 * every frame's, one choice for the run) is over SPECTRAL_AUTO_RGB_KEEP, the fewest wavelengths within the default
 * colour budget SPECTRAL_AUTO_BUDGET (spectral_pick), said on one stdout line. A run the spectral path cannot render
 * (`impossible`: the caller's reason, e.g. a composite; spectral_render_unable's; --bench) keeps RGB and says why on
 * stdout; the window keeps RGB silently (interactive). Not with a colour choice of its own (--spectral,
 * --max-color-error). Sets o->spectral; returns it (0: RGB kept). */
#define SPECTRAL_AUTO_BUDGET 1.0
#define SPECTRAL_AUTO_RGB_KEEP 3.0
int spectral_auto(options *o, const char *impossible);

/* The spectral sum rgb (RGBA floats, linear Rec.709 in the HDR image's units, r's size) tone-mapped into display
 * (RGBA8 sRGB) at v's exposure, or metered on the host under v->auto_exposure (one stderr line unless quiet):
 * the GPU tone map's law without bloom or dither (docs/spectral.md). */
void spectral_render_tonemap(const sky_renderer *r, const sky_view *v, const float *rgb, void *display);
/* The same for an image of w x h (a host of include/vksky.h: app/runs/spectral_host.c): every_pixel, whether the
 * meter counts the ground's pixels too (a lit ground); bottom_radius, the planet's (km). */
void spectral_render_tonemap_image(const sky_view *v, int w, int h, bool every_pixel, double bottom_radius,
                                   const float *rgb, void *display);

#endif
