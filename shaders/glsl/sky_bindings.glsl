/* Bindings of the sky pass (fragment or compute): set 0 = atmosphere UBO, the two LUTs, the sky-view LUT (only
 * the lookup variant declares it, so the march variant never reads an image it does not need), and for compute
 * the HDR storage image. Each mode is compiled separately (SKY_LOOKUP defined or not): its own pipeline, no
 * per-pixel branch. */
layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = VKSKY_BINDING_GROUND_IRRADIANCE_LUT) uniform sampler2D ground_irradiance_lut;
#ifdef SKY_BLEND
#define SKY_LOOKUP 1   /* the blend variant is the lookup's, with the march beside it (below) */
#endif
#if defined(SKY_FILL)
/* The bandwidth floor for benchmarks: a constant written to every pixel. */
#define SKY_RADIANCE(h, v, s, march) vec3(0.25, 0.5, 1.0)
#elif defined(SKY_LOOKUP)
layout(set = 0, binding = VKSKY_BINDING_SKYVIEW_LUT) uniform sampler2D skyview_lut;
#define VKSKY_SKYVIEW_LOOKUP 1
#define SKY_RADIANCE(h, v, s, march) sky_radiance_lookup(h, v, s)
#ifdef SKY_BLEND
/* High in the atmosphere the lookup blends into each pixel's own march (horizon.glsl: sky_eval). */
#define SKY_RADIANCE_DIRECT(h, v, s, march) sky_radiance(h, v, s, march, push.sun_dir.w)
#endif
#else
#define SKY_RADIANCE(h, v, s, march) sky_radiance(h, v, s, march, push.sun_dir.w)
#endif
layout(push_constant) uniform Push { SkyPush push; };
