/* The composite in spectral colour (--spectral N with --composite or --aovs; issue 32): every group of three wavelengths
 * (vksky_scene_spectral_group) composited band by band through its own renderer and composite pass of
 * include/vksky.h, the groups' layers summed on the host into linear Rec.709:
 *  - the light layers (sky, sun_disk, rayleigh, mie) with the groups' XYZ weights, as a spectral still's pixels;
 *  - the transmittance, which acts on the render's RGB beauty, as what a grey surface lit by the sun's spectrum keeps
 *    through the medium, per Rec.709 channel: T_q = sum over wavelengths of w_q(l) T(l) / sum of w_q(l), w_q(l)
 *    the Rec.709 channel q of the wavelength's XYZ weight (the solar spectrum times the CIE 1931 observer). Exact
 *    for a grey beauty in sunlight of the solar spectrum's colour, an approximation for a coloured one
 *    (docs/aerial_perspective.md, "Spectral colour");
 *  - the composite rebuilt from the summed layers by the coverage identity
 *      composite.rgb = beauty.rgb * transmittance + alpha (rayleigh + mie) + sky + sun_disk,
 *    so the identity holds on the spectral composite as on the RGB one.
 * A host of the API: no src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_COMPOSITE_SPECTRAL_H
#define VKSKY_APP_COMPOSITE_SPECTRAL_H

#include "app/runs/composite_bands.h"

/* Every band of `b` composited at `wavelengths` (a multiple of 3 or 4 the API takes, three to a pass) over the scene
 * `scene` (the command line's), with the composite's shape `desc` (one slot) and view `view` of the whole image,
 * summed and streamed into `out` (aborted on failure). 0, or 1 after one line on stderr. */
int composite_spectral_bands(band_reader *b, host_commands *h, vksky_context *ctx, const vksky_scene *scene,
                             int wavelengths, const vksky_composite_desc *desc, const vksky_composite_view *view,
                             FILE *trace, io_exr_layers_stream *out);

/* --aovs' layers at `wavelengths`: the composite pass of a frame with no geometry (desc: the whole image, one band;
 * view: the sky frame's camera, its altitude as given) through every group, summed. *layers: VKSKY_COMPOSITE_LAYERS
 * layers of width x rows RGBA floats one after the other (free()), or NULL on failure. 0, or 1 after one line. */
int composite_spectral_aovs(host_commands *h, vksky_context *ctx, const vksky_scene *scene, int wavelengths,
                            const vksky_composite_desc *desc, const composite_view *view, FILE *trace,
                            float **layers);

#endif
