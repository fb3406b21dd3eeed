/* Every descriptor binding of every pass, named once for C and GLSL (included by both through shared.h).
 *
 * All sets are set 0. The passes over the atmosphere (the LUT passes, the sky pass, the aerial-perspective volume, the
 * composite) share one table: a resource has one slot in every pass that binds it (the transmittance LUT is
 * binding 1 wherever it is sampled), and the image a compute pass writes is always VKSKY_BINDING_OUTPUT. The post
 * passes (bloom, tone map) share a second table. A pass binds only the slots it uses (gpu_set_layout takes a list
 * of (slot, type) pairs), so the numbers may have gaps. */
#ifndef VKSKY_BINDINGS_H
#define VKSKY_BINDINGS_H

/* The atmosphere passes. */
#define VKSKY_BINDING_ATMOSPHERE 0            /* uniform block AtmosphereParams (shared.h) */
#define VKSKY_BINDING_TRANSMITTANCE_LUT 1     /* sampled */
#define VKSKY_BINDING_MULTISCATTER_LUT 2      /* sampled (the transmittance LUT without multi-scattering) */
#define VKSKY_BINDING_SKYVIEW_LUT 3           /* sampled */
#define VKSKY_BINDING_GROUND_IRRADIANCE_LUT 4 /* sampled (the transmittance LUT without a lit ground) */
#define VKSKY_BINDING_AP_VOLUME 5             /* sampled: the froxel volume of --aerial-perspective volume */
#define VKSKY_BINDING_COMPOSITE_IN 6          /* sampled: the composite's uploaded beauty and world position */
#define VKSKY_BINDING_OUTPUT 7                /* storage image: what the compute pass writes (a LUT, the HDR image,
                                                 the froxel volume, the composite's layers, the host's colour
                                                 image of the library's SCENE_LINEAR pass) */
#define VKSKY_BINDING_HOST_DEPTH 8            /* sampled: the host's depth (the library's SCENE_LINEAR pass) */

/* The post passes. */
#define VKSKY_BINDING_POST_SOURCE 0           /* sampled: the HDR image, or the mip a bloom pass reads */
#define VKSKY_BINDING_POST_MIP 1              /* bloom mip: written by a compute bloom pass; in the single pass mip k
                                                 is POST_MIP + k; the tone maps sample mip 0 (and 1) here */
#define VKSKY_BINDING_SPD_COUNTERS 9          /* the single pass's tile counters (POST_MIP + BLOOM_MAX_MIPS) */
#define VKSKY_BINDING_TONEMAP_DISPLAY 3       /* storage: the compute tone map's display image */
#define VKSKY_BINDING_TONEMAP_COMPOSITE 4     /* storage: the compute tone map's linear composite */
#define VKSKY_BINDING_METER 10                /* storage buffer: the exposure meter's partials and results (meter.comp;
                                                 the tone maps read a result) */
#define VKSKY_BINDING_SPECTRAL_GROUP 0      /* sampled: a spectral group's composite (spectral_sum.comp, its own set) */
#define VKSKY_BINDING_SPECTRAL_SUM 1        /* storage image: the float32 XYZ sum */
#define VKSKY_BINDING_SPECTRAL_RESOLVED 2   /* storage buffer: the resolved frame, host-visible */

#endif
