/* Physical light (issue 32): what a pixel means. In photometric units (the default) the sun is the solar spectrum
 * at the top of the atmosphere (model/spectrum.h: linear Rec.709 whose Y is its illuminance in lux, 1.33e5 lx) and a
 * pixel is linear Rec.709 whose Y is luminance in cd/m2; exposure is EV100. In relative units (--units relative)
 * everything is the lesson's: the sun 20,20,20, exposure in stops. docs/units.md explains both.
 *
 * The sun as given (--sun-illuminance, the scene's sun.illuminance / sun.lux / sun.spectrum_scale) is kept in the
 * lesson's scale, where 20,20,20 is the real sun: photometric units read it as that fraction of the solar spectrum,
 * channel by channel, so that old scene files keep their meaning (twice the sun stays twice the sun).
 *
 * The GPU's HDR images are half floats (largest value 65504): photometric frames are rendered at light_scale cd/m2
 * (a power of two, exact both ways) chosen so that the disc, the brightest thing in the sky, fits; the EXR writers
 * divide it out. */
#ifndef VKSKY_APP_LIGHT_H
#define VKSKY_APP_LIGHT_H
#include "app/cli/options_struct.h"
#include "io/exr_sky_attrs.h"
#include <stddef.h>
#include <stdint.h>

#define LIGHT_RELATIVE_SUN 20.0   /* the lesson's sun, which photometric units read as the real one */

/* The sun at the top of the atmosphere in the output's units: lux-weighted Rec.709 (photometric) or as given. */
void light_sun(const options *o, double out[3]);
/* The sun's illuminance at the camera (through the atmosphere; 0 when the planet hides it), output units. */
void light_sun_at_camera(const options *o, double out[3]);
/* The HDR image's units per output unit: 1 (relative) or a power of two (photometric). */
double light_scale(const options *o);
/* The medium the GPU renders: the sun in the HDR image's units. */
void light_render_atmosphere(const options *o, model_atmosphere *out);
/* Sets what the renderer needs of the units (the view's exposure law and scale). Call once the options are final. */
void light_finish(options *o);
/* --sun-lux / the scene's sun.lux: the sun whose illuminance at the top of the atmosphere is `lux`: the solar
 * spectrum scaled (in relative units the lesson's white sun, 20 for the real sun's 1.33e5 lx). */
void light_set_sun_lux(options *o, double lux);

/* Output pixels of an EXR: the renderer's RGBA half pixels in output units (divided by light_scale), as floats
 * (malloc'd, NULL: out of memory); *store_float: whether the file stores FLOAT (--exr-type, or auto: any value over
 * half's range). */
float *light_exr_pixels(const options *o, const uint16_t *rgba_half, size_t pixels, bool *store_float);
/* The same into `out` (pixels * 4 floats), on the calling thread's encode threads (io/encode_settings.h). */
void light_exr_pixels_into(const options *o, const uint16_t *rgba_half, size_t pixels, float *out, bool *store_float);
/* Whether an environment map (streamed before its pixels exist) is stored FLOAT: --exr-type, or auto: photometric
 * with the disc drawn and the sun above the camera's horizon. */
bool light_stream_float(const options *o);
/* The EXR attributes that name units: "vksky:units", the sun's ("lx" or "relative"), whiteLuminance. */
const char *light_units_text(const options *o);
const char *light_sun_units_text(const options *o);
/* The sun and unit attributes of every EXR (io/exr_sky_attrs.h): direction, illuminance at the top of the atmosphere
 * and at the camera in output units, the units' names, whiteLuminance (photometric: 1). envmap/projection untouched. */
void light_sky_attrs(const options *o, io_exr_sky_attrs *a);

/* The rays of a perspective frame of v, width x height: the camera's unit basis (+Y up; sky/view_params.h's) and the
 * half-extents tan(fov/2) * width / height and tan(fov/2). Pixel position (x, y) in [-1, 1] (y = 1: the top row) looks
 * along forward + x tx right + y ty up. */
typedef struct view_rays {
    double forward[3], right[3], up[3];
    double tx, ty;
} view_rays;
view_rays light_view_rays(const sky_view *v, int width, int height);
/* The unit direction of continuous pixel position (x, y) of a width x height environment map of `projection` (sky_view's,
 * not perspective: sky/projection.h's projection_dir, for the hosts of include/vksky.h that may not include sky/);
 * false where the projection has none (outside a fisheye's circle). */
bool light_map_dir(int projection, int width, int height, double x, double y, double dir[3]);
/* The sine of the horizon's elevation seen from altitude_km above a planet of ground_radius_km (0 on the ground): a
 * ray whose elevation sine is below it meets the planet. */
double light_horizon_sine(double altitude_km, double ground_radius_km);

/* The window's luminance under the cursor (auto exposure itself is metered on the GPU: sky/meter.h): the CPU
 * reference's sky luminance (output units, cd/m2 in photometric units; the disc left out) along the view ray of
 * continuous pixel (x, y) of a width x height view, at a quality fit for an interactive readout (~1e-3 of the
 * converged reference, a few ms). */
double light_meter_pixel(const options *o, const sky_view *v, int width, int height, double x, double y);

/* Auto exposure (metered on the GPU: sky/meter.h; docs/units.md): the log-average (geometric mean) luminance of a
 * frame in cd/m2 (luminance floored at 1e-4 cd/m2 so a black pixel does not drag the mean to zero; with a black
 * ground only the sky's pixels count) and the EV100 that exposes it at the reflected-light meter's key:
 * EV100 = log2(L_avg S / K), S = 100, K = 12.5. */
double light_auto_ev100(double log_average_cd_m2);
/* Whether a headless frame is exposed automatically: --auto-exposure, or photometric units without a given exposure,
 * and a PNG among the outputs (an EXR's pixels do not depend on the exposure). */
bool light_auto_exposure_wanted(const options *o);
/* The view's exposure from a log-average luminance in the HDR image's units per light_scale (EV100, or in relative
 * units the stops that give the same multiplier 1 / (1.2 2^EV100)). */
void light_expose(sky_view *v, double log_average);
#endif
