/* Layouts shared by C and GLSL: one definition, included by both languages.
 * Every member is a vec4 so std140 (GLSL) and the C struct have the same layout with no padding rules to
 * remember. glslang defines VULKAN when compiling for Vulkan; the C compiler does not. */
#ifndef VKSKY_SHARED_H
#define VKSKY_SHARED_H

#include "bindings.h"   /* every pass's descriptor bindings */

#ifdef VULKAN
#define VKSKY_STRUCT(name) struct name
#define VKSKY_END(name) ;
#else
typedef struct vksky_vec4 { float x, y, z, w; } vksky_vec4;
#define vec4 vksky_vec4
#define VKSKY_STRUCT(name) typedef struct name
#define VKSKY_END(name) name;
#endif

#define VKSKY_MAX_EXTRA 2              /* species beyond Rayleigh, Mie and ozone (MODEL_MAX_EXTRA_SPECIES) */
#define VKSKY_SPECIES (3 + VKSKY_MAX_EXTRA)

/* The atmosphere: uniform buffer, set 0 binding 0 of every sky shader. Changes only when the scene does. */
VKSKY_STRUCT(AtmosphereParams) {
    vec4 radii;                /* x: bottom (ground) radius km, y: top radius km, z: top - bottom (from double) */
    vec4 rayleigh_scattering;  /* rgb: sigma_s /km at density 1 */
    vec4 mie_scattering;       /* rgb: sigma_s /km */
    vec4 mie_absorption;       /* rgb: sigma_a /km, w: Mie phase g */
    vec4 ozone_absorption;     /* rgb: sigma_a /km */
    vec4 extra_scattering[VKSKY_MAX_EXTRA];  /* rgb: sigma_s /km of the extra species (Rayleigh phase) */
    vec4 extra_absorption[VKSKY_MAX_EXTRA];  /* rgb: sigma_a /km of the extra species */
    vec4 profile_widths[2];    /* [species / 4][species % 4]: layer 0's top (km) of each density profile */
    vec4 profiles[2 * VKSKY_SPECIES];
                               /* [2 species + layer]: (exp_term, exp_scale /km, linear_term /km, constant_term):
                                  density = clamp(exp_term exp(exp_scale h) + linear_term h + constant_term, 0, 1),
                                  Bruneton's DensityProfileLayer; species 0 Rayleigh, 1 Mie, 2 ozone, 3.. extra */
    vec4 sun;                  /* rgb: illuminance, w: angular radius (rad) */
    vec4 lut_steps;            /* x: transmittance steps, y: multiscatter steps, z: multiscatter sqrt(directions) */
    vec4 ground;               /* rgb: ground albedo (Lambertian), w: sun limb darkening coefficient u */
    vec4 sun_disc;             /* x: 1 the disc carries the sun's power (its radiance integrates to sun.rgb x the
                                  transmittance), 0 the lesson's disc (sun.rgb x 10, --units relative); yzw: unused */
#if !defined(VULKAN) || defined(SPECTRAL4)
    vec4 scalars4;             /* the four-wide spectral build (SPECTRAL4): x Mie phase g, y the sun's angular radius,
                                  z limb darkening u, w: 1 (their .w slots above carry the fourth wavelength's
                                  coefficient, illuminance and albedo); zero and not declared in the RGB shaders */
#endif
} VKSKY_END(AtmosphereParams)

/* Sky pass (and sky-view LUT) push constants: the camera as altitude + directions (never an absolute
 * planet-scale position). */
VKSKY_STRUCT(SkyPush) {
    vec4 forward;              /* xyz: view axis (unit),          w: camera altitude km (>= 0) */
    vec4 right;                /* xyz: right * tan(fov/2)*aspect, w: 1 / output width */
    vec4 up;                   /* xyz: up * tan(fov/2),           w: 1 / output height */
    vec4 sun_dir;              /* xyz: unit direction toward the sun (camera up = +Y), w: step distribution
                                  exponent p (steps end at t_max (i/N)^p: 1 uniform, 2 quadratic) */
    vec4 march;                /* x: min steps, y: max steps (= min: fixed count), z: sample position in a step
                                  (0.5 midpoint, 0.3 Hillaire), w: km of path at which the count reaches max */
    vec4 projection;           /* x: VKSKY_PROJECTION_*, yz: this tile's pixel offset in the whole image (right.w
                                  and up.w are 1 / the whole image's size), w: unused (shaders/glsl/projection.glsl) */
    vec4 horizon;              /* the planet's edge (shaders/glsl/horizon.glsl): x: sine of the horizon's elevation
                                  from the camera, -sqrt(h (2R + h)) / (R + h), computed in double on the CPU; y: 1 =
                                  the sky image is the output's size (informative: the tone map resolves coverage
                                  at every scale, hdr_upsample.glsl); z: the sky-view lookup's blend toward the
                                  march (the blend variant), 0 up to a quarter of the atmosphere's height,
                                  linearly to 1 at its top (where --sky-mode auto hands over to the march: no pop on
                                  the way to space); w: the same for the rays near the horizon and below 3 degrees,
                                  0 up to a tenth of the atmosphere's height, 1 from three tenths */
} VKSKY_END(SkyPush)

/* Composite pass push constants (composite.comp): aerial perspective from the camera to each pixel's point, and
 * the sky along the rays of pixels without geometry. The march frame is the sky pass's, at the camera: up = +Y
 * (the local vertical), km. 8 vec4 = 128 bytes, the push-constant size every device has. */
VKSKY_STRUCT(CompositePush) {
    vec4 forward;              /* xyz: view axis in the march frame (zero: orientation unknown, sky pixels keep
                                  the beauty), w: camera altitude km (from double on the CPU) */
    vec4 right;                /* xyz: right * tan(fov/2)*aspect, w: the first row of the band composited (the
                                  width is the band's: composite.comp reads it from its input image) */
    vec4 up;                   /* xyz: up * tan(fov/2),           w: 1 / height (the whole frame's) */
    vec4 sun_dir;              /* xyz: toward the sun in the march frame, w: step distribution exponent */
    vec4 march;                /* as SkyPush.march: min steps, max steps, sample position, km at max steps */
    vec4 world_to_march[3];    /* rows of the 3x3 matrix from a world-unit offset to march-frame km (axis swap,
                                  unit scale and the tilt of the local vertical); w: the camera's world position */
} VKSKY_END(CompositePush)

/* The composite's sky tiles (composite.comp): 8x8 pixels from the band's first row. The host marks a tile none of
 * whose pixels shows sky (alpha >= 1 on all of them) by this value in the w of its first pixel's position (the
 * position's w is otherwise unused): the shader then skips the tile's five sky rays without reading its 64 alphas.
 * Any other w (1, NaN) marches them. */
#define VKSKY_COMPOSITE_TILE 8
#define VKSKY_COMPOSITE_TILE_NO_SKY (-1.0)

/* The composite pass's output: one RGBA32F image of VKSKY_AOV_COUNT bands of `height` rows each, band k the k-th
 * layer (one image: one barrier, one copy). */
#define VKSKY_AOV_COMPOSITE 0      /* RGBA: beauty * T + rayleigh + mie on geometry, the sky (+ sun disc) elsewhere */
#define VKSKY_AOV_SKY 1            /* sky without the sun disc (pixels without geometry) */
#define VKSKY_AOV_SUN_DISK 2       /* the sun disc alone, through the atmosphere */
#define VKSKY_AOV_TRANSMITTANCE 3  /* camera -> point (geometry) or along the whole ray (sky) */
#define VKSKY_AOV_RAYLEIGH 4       /* in-scattering with the Rayleigh phase (+ its multiple scattering) */
#define VKSKY_AOV_MIE 5            /* in-scattering with the Mie phase (+ its multiple scattering) */
#define VKSKY_AOV_COUNT 6

/* How a pixel maps to a view direction (shaders/glsl/projection.glsl; its C twin src/sky/projection.c). */
#define VKSKY_PROJECTION_PERSPECTIVE 0
#define VKSKY_PROJECTION_EQUIRECT 1     /* 2:1 latitude-longitude, OpenEXR/OpenImageIO's latlong axes (+Y up) */
#define VKSKY_PROJECTION_CUBEMAP 2      /* OpenEXR's cube: faces +X -X +Y -Y +Z -Z stacked top to bottom */
#define VKSKY_PROJECTION_FISHEYE 3      /* equidistant upper hemisphere, zenith at the centre, north up, east left */

/* Bloom push constants. */
VKSKY_STRUCT(BloomPush) {
    vec4 src_texel;            /* xy: 1/size of the source image, z: 1 = first downsample (threshold + Karis), w: threshold */
} VKSKY_END(BloomPush)

/* Tone map push constants. */
VKSKY_STRUCT(TonemapPush) {
    vec4 params;               /* x: exposure (linear multiplier), y: operator (0 clamp, 1 Reinhard, 2 ACES),
                                  z: bloom strength (0 = no bloom), w: 1 = encode sRGB in the shader */
    vec4 dither;               /* x: 1 = triangular dither of the 8-bit output (shaders/glsl/dither.glsl), 0 = off;
                                  yz: the frame's pixel offset in the whole image (a tile's), so the noise is seeded
                                  by the whole image's pixel; w: a tiled render's whole height in pixels (0: the
                                  frame is the whole image), where the upsample's taps stop (hdr_upsample.glsl) */
    vec4 meter;                /* x: 1 = auto exposure: params.x is multiplied by the GPU meter's exposure (meter.comp,
                                  the result of slot y); 0: params.x alone */
} VKSKY_END(TonemapPush)

/* Compute post chain push constants (bloom_spd.comp, bloom_up.comp, tonemap.comp). */
VKSKY_STRUCT(PostPush) {
    vec4 params;               /* spd: x mip count, y threshold; up: xy 1/size of the smaller (source) mip */
    vec4 tonemap;              /* tonemap.comp: TonemapPush's params (exposure, operator, bloom strength, sRGB) */
    vec4 bloom;                /* tonemap.comp: xy 1/size of bloom mip 1, z 1 = add its tent (the fused last upsample) */
    vec4 dither;               /* tonemap.comp: TonemapPush's dither */
    vec4 meter;                /* tonemap.comp: TonemapPush's meter */
} VKSKY_END(PostPush)

/* The exposure meter (meter.comp, issue 32): the log-average luminance of the HDR image, on the GPU. Pass 0: one
 * workgroup of 16 x 16 threads per VKSKY_METER_TILE^2 texels writes (sum of ln L, count) into partial[group]; pass
 * 1: one workgroup adds the partials and writes result[slot] = (L_avg cd/m2, EV100, the tone map's multiplier,
 * pixels counted), and the adapted EV100 the next frame eases from. One result slot per frame in flight, so the host
 * reads a finished frame's while the next runs. */
#define VKSKY_METER_TILE 64
#define VKSKY_METER_SLOTS 4
VKSKY_STRUCT(MeterPush) {
    vec4 params;               /* x: the HDR image's units per cd/m2 (light_scale), y: the luminance floor in cd/m2,
                                  z: 1 = every pixel counts (a lit ground), 0 = sky pixels only (HDR alpha >= 0),
                                  w: the result slot (pass 1); pass 0: 1 = a fisheye, only texels inside its circle */
    vec4 pass;                 /* x: 0 = tiles, 1 = the average; y: the number of partials (pass 1), the first row
                                  counted (pass 0); z: the fraction of the way from the last frame's EV100 to this
                                  frame's metered one (temporal adaptation, the window: 1 - exp(-dt / tau); 1 or more:
                                  none, the metered EV100; pass 0: a fisheye band's first row in the whole image); w: one past the last row counted (pass 0: a band's own rows,
                                  vksky_frame_band; a whole frame counts every row) */
} VKSKY_END(MeterPush)

/* The spectral sum's push constants (spectral_sum.comp, src/sky/spectral_sum.c; issue 32): 8 vec4 = 128 bytes. */
VKSKY_STRUCT(SpectralSumPush) {
    /* weight[c].xyz: CIE XYZ per unit of the group image's channel c (its wavelength's bin, vksky_scene_spectral_group);
     * 0 for a channel past the last wavelength (three to a pass: channel 3 is the composite's coverage, weight 0). */
    vec4 weight[4];
    /* x: 1 = the frame's first group (the sum starts at 0), y: 1 = the last (the sum resolved into the output buffer),
     * z: the resolved alpha: 1 = the group image's (three to a pass: the composite's coverage), 0 = 1.0,
     * w: the group image's width in pixels */
    vec4 mode;
    /* The XYZ -> linear Rec.709 matrix's rows (xyz; spectrum_xyz_to_rec709's, in float): one definition, the C side's */
    vec4 to_rec709[3];
} VKSKY_END(SpectralSumPush)

/* The multi-scattering LUT pass (multiscatter_lut.comp, issue 31): with a lit ground it runs twice, the second time
 * with its ground lit by the sky too (the ground-irradiance LUT that the first pass's LUT made; docs/model.md
 * "Lit ground"). */
VKSKY_STRUCT(MultiscatterPush) {
    vec4 ground;               /* x: 1 = the ground term adds the sky's irradiance (the ground-irradiance LUT), 0 =
                                  the sun's alone (Hillaire's; the first pass, whose ground-irradiance slot holds a
                                  stand-in never sampled); yzw: unused */
} VKSKY_END(MultiscatterPush)

/* Specialization constants: what a scene needs, compiled in; what it does not, compiled out (one pipeline
 * per variant, no per-pixel branch). The same IDs in every shader that includes atmosphere.glsl. */
#define VKSKY_SPEC_RAYLEIGH 1
#define VKSKY_SPEC_MIE 2
#define VKSKY_SPEC_OZONE 3
#define VKSKY_SPEC_MULTISCATTER 4
#define VKSKY_SPEC_SUN_DISC 5
#define VKSKY_SPEC_GROUND 6
#define VKSKY_SPEC_MIE_PHASE 7
#define VKSKY_SPEC_RAYLEIGH_PROFILE 8  /* the density profile's form, per species: */
#define VKSKY_SPEC_MIE_PROFILE 9
#define VKSKY_SPEC_OZONE_PROFILE 10
#define VKSKY_PROFILE_EXPONENTIAL 0     /* exp(b h), one layer: one exp, no layer select, no clamp */
#define VKSKY_PROFILE_LINEAR 1          /* two layers without exponential terms (the ozone tent): no exp */
#define VKSKY_PROFILE_GENERAL 2         /* any pair of Bruneton layers */
#define VKSKY_SPEC_EXTRA_SPECIES 11     /* how many extra species (0 .. VKSKY_MAX_EXTRA) */
#define VKSKY_SPEC_EXTRA0_PROFILE 12
#define VKSKY_SPEC_EXTRA1_PROFILE 13
#define VKSKY_SPEC_SUN_VISIBILITY 14   /* VKSKY_SUN_VISIBILITY_*: the penumbra or the lesson's horizon fade */
#define VKSKY_SPEC_COUNT 14             /* IDs 1 .. 14: the scene's variant (every pipeline of the renderer) */
#define VKSKY_SUN_VISIBILITY_PENUMBRA 0 /* = MODEL_SUN_VISIBILITY_* (src/model/sun_visibility.h) */
#define VKSKY_SUN_VISIBILITY_LESSON_FADE 1
#define VKSKY_SPEC_AP_RANGE 15          /* the aerial-perspective volume's (ap_volume.c): its range in km */
#define VKSKY_SPEC_AP_DISTRIBUTION 16   /* and its slice distribution exponent (1 linear, 2 quadratic) */
#define VKSKY_SPEC_TONEMAP_FAR 17       /* the fragment tone map's far-only variant (sky/tonemap_regions.h) */
/* The multi-scattering LUT is an atlas of this many N x N parts side by side (multiscatter_lut.comp): Psi^(1/4)
 * and D; Q_zz, Q_xz, m_x, m_z; the zonal moments of degrees 3 to 6. */
#define VKSKY_MULTISCATTER_PARTS 3
/* The four-wide spectral build (SPECTRAL4): Psi^(1/4) fills the first part's four channels, so D moves to a fourth
 * part (D, 0, 0, 0). */
#define VKSKY_MULTISCATTER_PARTS4 4
#define VKSKY_MIE_PHASE_HG 0
#define VKSKY_MIE_PHASE_CORNETTE_SHANKS 1

#define VKSKY_TONEMAP_CLAMP 0
#define VKSKY_TONEMAP_REINHARD 1
#define VKSKY_TONEMAP_ACES 2

#ifndef VULKAN
#undef vec4
#endif
#endif
