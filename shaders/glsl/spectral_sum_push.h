/* The spectral sum's push constants (spectral_sum.comp, src/sky/spectral_sum.c): one definition for C and GLSL
 * (include shared.h first). 8 vec4 = 128 bytes, the push-constant size every device has. */
#ifndef VKSKY_SPECTRAL_SUM_PUSH_H
#define VKSKY_SPECTRAL_SUM_PUSH_H
#include "shared.h"
#ifndef VULKAN
#define vec4 vksky_vec4   /* shared.h's C spelling, undefined at its end */
#endif

VKSKY_STRUCT(SpectralSumPush) {
    /* weight[c].xyz: CIE XYZ per unit of the group image's channel c (its wavelength's bin, vksky_scene_spectral_group);
     * 0 for a channel past the last wavelength. */
    vec4 weight[4];
    /* x: 1 = the group's first (the sum starts at 0), y: 1 = the last (the sum resolved into the output buffer),
     * z: the resolved alpha: 1 = the group image's (three to a pass: the composite's coverage), 0 = 1.0,
     * w: the group image's width in pixels */
    vec4 mode;
    /* The XYZ -> linear Rec.709 matrix's rows (xyz; spectrum_xyz_to_rec709's, in float): one definition, the C side's */
    vec4 to_rec709[3];
} VKSKY_END(SpectralSumPush)
#ifndef VULKAN
#undef vec4
#endif
#endif
