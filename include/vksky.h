/* vksky: Hillaire's sky and atmosphere (EGSR 2020) as a C library over Vulkan 1.3.
 *
 * The host owns the instance, the device, the queue, its command buffers and its images. vksky builds its LUTs,
 * its pipelines and its own intermediate images on the host's device and records its passes into a command
 * buffer the host gives it, writing the host's images; it never creates a device when given one, never submits
 * per frame, never calls exit(), never prints: every call returns a vksky_result and every message goes to the
 * host's callback. docs/library.md is the integration recipe; docs/synchronization.md's chapter "A library in a
 * frame it does not own" is the contract each image follows.
 *
 * Include your Vulkan header (<vulkan/vulkan.h>, or <volk.h>) before this one; vksky.h includes
 * <vulkan/vulkan_core.h> itself only when neither was included.
 *
 * Threads: calls on one context, or on renderers of one context, must not overlap (one thread at a time, or the
 * host's lock); different contexts are independent. vksky_record only records: the host submits the command buffer,
 * and must not destroy a renderer or change its scene while a command buffer it recorded is pending. vksky never
 * points the process's stdout or stderr elsewhere: a scene's load (vksky_scene_load, vksky_scene_from_args,
 * vksky_scene_reload) and a frame's values (vksky_scene_set_values) capture the loader's one line (for `message`) on
 * the calling thread only, so the lines the host's other threads print meanwhile stay theirs.
 *
 * Units: lengths in metres unless a name says otherwise; angles in degrees; +Y up in the host's world, the ground
 * (the planet's surface) at y = 0 below the world origin unless vksky_camera.origin_altitude_m says otherwise. */
#ifndef VKSKY_H
#define VKSKY_H
#if !defined(VULKAN_CORE_H_)
#include <vulkan/vulkan_core.h>
#endif
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(VKSKY_BUILDING_LIBRARY) && defined(__GNUC__)
#define VKSKY_API __attribute__((visibility("default")))
#else
#define VKSKY_API
#endif

/* The ABI this header describes. A host passes it in every *_desc; a library built for another ABI refuses the
 * call with VKSKY_ERROR_ABI_MISMATCH instead of reading a struct of another shape.
 * 2: vksky_renderer_desc and vksky_frame gained `next` (extension chains), vksky_quality_config,
 *    vksky_renderer_get_timings; the compute queue (vksky_context_desc.compute_queue, vksky_record_luts);
 *    vksky_readback_config, vksky_frame_view, vksky_scene_from_args, vksky_renderer_get_readback,
 *    vksky_context_set_device_features, vksky_auto_exposure + vksky_renderer_get_exposure,
 *    vksky_context_set_cache_directory + vksky_renderer_store_luts; vksky_frame_band (projections, bands);
 *    readback slots (vksky_readback_target), vksky_scene_set_values, vksky_renderer_scene_changes, vksky_renderer_luts_stale (sequences);
 *    vksky_renderer_get_stats (--timings); vksky_scene_reload (F5).
 * 3: the window's frame extensions: vksky_frame_display (tone map, bloom), vksky_frame_place (altitude, sun),
 *    vksky_frame_timer + vksky_renderer_get_slot_timings, vksky_frame_capture + vksky_renderer_get_capture,
 *    vksky_frame_swapchain (a swapchain image's barriers); vksky_context_set_debug_utils (names, labels);
 *    vksky_renderer_get_lut_timings (--bench --async-luts); vksky_device_requirements' limits;
 *    spectral groups as scenes (vksky_scene_spectral_group, vksky_scene_spectral_coefficients,
 *    vksky_spectral_group_count, vksky_spectral_xyz_to_rec709): the command line's --spectral N through the API.
 * 4: compositing a render (vksky_composite_*: the command line's --composite and --aovs); the tone map's path into
 *    the host's image (vksky_display_config + vksky_renderer_get_tonemap_path: the compute tone map into a storage
 *    image); the spectral groups summed on the GPU (vksky_spectral_sum, vksky_frame_spectral_sum). */
#define VKSKY_ABI_VERSION 4u
VKSKY_API uint32_t vksky_abi_version(void);
VKSKY_API const char *vksky_version_string(void);   /* "0.1.0" */

typedef enum vksky_result {
    VKSKY_SUCCESS = 0,
    VKSKY_ERROR_INVALID_ARGUMENT = -1,   /* a NULL handle, a size of 0, an unknown name, a value out of range */
    VKSKY_ERROR_ABI_MISMATCH = -2,       /* desc.abi_version is not this library's VKSKY_ABI_VERSION */
    VKSKY_ERROR_UNSUPPORTED = -3,        /* the device lacks what vksky needs (Vulkan 1.3, a format, a feature) */
    VKSKY_ERROR_VULKAN = -4,             /* a Vulkan call failed (the message callback names it and its VkResult) */
    VKSKY_ERROR_OUT_OF_MEMORY = -5,      /* host or device memory */
    VKSKY_ERROR_IO = -6,                 /* a file could not be read */
    VKSKY_ERROR_PARSE = -7,              /* a scene file or EXR is malformed (the callback says where) */
    VKSKY_ERROR_DEVICE_LOST = -8
} vksky_result;
VKSKY_API const char *vksky_result_name(vksky_result result);

typedef enum vksky_severity {
    VKSKY_SEVERITY_INFO = 0,
    VKSKY_SEVERITY_WARNING = 1,
    VKSKY_SEVERITY_ERROR = 2,            /* the call that printed it returns an error */
    VKSKY_SEVERITY_VALIDATION = 3        /* the validation layer (only with a context vksky created, validation on) */
} vksky_severity;
/* One message, one line, no trailing newline. Called on the thread that made the vksky call. */
typedef void (*vksky_message_fn)(void *user, vksky_severity severity, const char *message);

typedef struct vksky_context vksky_context;      /* the device vksky works on: the host's, or its own */
typedef struct vksky_scene vksky_scene;          /* planet, medium, sun: a value, no GPU state */
typedef struct vksky_renderer vksky_renderer;    /* LUTs, pipelines, intermediate images for one output size */

/* ---- Contexts ------------------------------------------------------------------------------------------------- */

/* The host's device. It must be Vulkan 1.3 with the features of vksky_device_requirements enabled. */
typedef struct vksky_context_desc {
    uint32_t abi_version;                            /* VKSKY_ABI_VERSION */
    PFN_vkGetInstanceProcAddr get_instance_proc_addr;   /* the host's loader entry (vksky keeps no global loader
                                                           state of the host's: its function pointers are its own) */
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    uint32_t queue_family;                           /* the family whose command buffers vksky_record receives */
    uint32_t queue_index;                            /* the queue vksky may submit its one-time work to (uploads at
                                                        creation); vksky_record never submits */
    const VkAllocationCallbacks *allocator;          /* NULL: Vulkan's default; used for every object vksky makes */
    VkPipelineCache pipeline_cache;                  /* the host's, or VK_NULL_HANDLE */
    vksky_message_fn message;                        /* NULL: messages are dropped */
    void *message_user;
    /* ABI 2: the compute queue whose command buffers vksky_record_luts receives (the LUTs on an async compute queue,
     * docs/library.md). Another family than queue_family: the LUT images change owner (vksky records both halves). */
    bool compute_queue;
    uint32_t compute_queue_family, compute_queue_index;
} vksky_context_desc;

/* What the host must enable on its device for vksky: Vulkan 1.3 core features (synchronization2, dynamicRendering,
 * maintenance4: glslang's SPIR-V for Vulkan 1.3 declares compute workgroup sizes with LocalSizeId),
 * and optionally vulkanMemoryModel + vulkanMemoryModelDeviceScope (the single-pass bloom downsample). Fills the
 * booleans the host should set in its VkPhysicalDeviceVulkan13Features / 12Features chain. */
typedef struct vksky_device_requirements {
    bool synchronization2, dynamic_rendering;       /* required */
    bool maintenance4;                              /* required (VkPhysicalDeviceVulkan13Features.maintenance4) */
    bool vulkan_memory_model, vulkan_memory_model_device_scope;   /* optional: used when enabled */
    /* ABI 2: the VkPhysicalDeviceLimits vksky's pipelines need, where they exceed Vulkan 1.3's required minimums (or
     * may grow past them). vksky_context_create / _create_own refuse a device below one (VKSKY_ERROR_UNSUPPORTED,
     * a message naming the limit, the device's value and the need). The shared memory is the single-pass bloom's:
     * a device with less runs the per-level chain instead (an info message), and needs only the LUT passes'. */
    uint32_t max_compute_work_group_invocations;      /* 256: the exposure meter's 16 x 16 workgroups (spec: 128) */
    uint32_t max_per_stage_descriptor_storage_images; /* 9: the single-pass bloom's counters + 8 mips (spec: 4) */
    uint32_t max_compute_shared_memory_size;          /* 24,260 bytes with the single pass (spec: 16,384) */
    uint32_t max_push_constants_size;                 /* 128 bytes (spec: 128) */
} vksky_device_requirements;
VKSKY_API void vksky_get_device_requirements(vksky_device_requirements *out);

VKSKY_API vksky_result vksky_context_create(const vksky_context_desc *desc, vksky_context **out);
/* The optional features the host enabled on its device (a VkDevice cannot be asked): with vulkan_memory_model and
 * vulkan_memory_model_device_scope both true the single-pass bloom downsample may run (else the per-level chain
 * does). The required ones must be true. Call before creating renderers; a context vksky made knows its own. */
VKSKY_API vksky_result vksky_context_set_device_features(vksky_context *context,
                                                         const vksky_device_requirements *enabled);

/* ABI 2: the host enabled VK_EXT_debug_utils on its instance (an instance cannot be asked): vksky then names the
 * objects it makes ("vksky.transmittance_lut", "vksky.sky_pipeline", ...) and labels what it records: a
 * "vksky.record" label around each vksky_record ("vksky.record_luts" around vksky_record_luts) holding one label per
 * pass ("transmittance", "sky", "tonemap", ... as the trace names them), for RenderDoc or Nsight in the host's
 * frame. Off by default: without this call vksky makes no VK_EXT_debug_utils call at all. Call before the first
 * renderer (names are given at creation). A context vksky made names its objects whenever its instance has the
 * extension; `enabled` false turns that off. */
VKSKY_API vksky_result vksky_context_set_debug_utils(vksky_context *context, bool enabled);

/* vksky makes its own instance and device (the command-line tool, the window, tests). */
typedef struct vksky_own_device_desc {
    uint32_t abi_version;                            /* VKSKY_ABI_VERSION */
    int device_index;                                /* -1: pick (discrete > integrated > virtual > CPU) */
    bool validation;                                 /* Khronos validation + synchronization validation; its
                                                        messages go to the callback as VKSKY_SEVERITY_VALIDATION */
    const char *const *instance_extensions;          /* extra (e.g. from glfwGetRequiredInstanceExtensions) */
    uint32_t instance_extension_count;
    bool swapchain;                                  /* enable VK_KHR_swapchain on the device */
    vksky_message_fn message;
    void *message_user;
    /* ABI 2: also make a compute queue (a compute-only family, else a second queue of the graphics family; else
     * VKSKY_ERROR_INVALID_ARGUMENT), for vksky_record_luts; vksky_context_get_handles reports it. */
    bool compute_queue;
} vksky_own_device_desc;
VKSKY_API vksky_result vksky_context_create_own(const vksky_own_device_desc *desc, vksky_context **out);

/* Destroys what vksky made (its device too, for vksky_context_create_own). Every renderer of the context must be
 * destroyed first. NULL is ignored. */
VKSKY_API void vksky_context_destroy(vksky_context *context);

/* The handles of a context (its own device's, or the host's as given). */
typedef struct vksky_context_handles {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkQueue compute_queue;          /* ABI 2: VK_NULL_HANDLE without one */
    uint32_t compute_queue_family;
} vksky_context_handles;
VKSKY_API void vksky_context_get_handles(const vksky_context *context, vksky_context_handles *out);

/* Validation messages seen by a context vksky created with validation on. */
VKSKY_API uint32_t vksky_context_validation_message_count(const vksky_context *context);

/* The context's own trace (docs/synchronization.md): while a call on this context records or submits (renderer
 * creation, set_scene, resize, vksky_record), each line `vksky --trace-barriers` / `--trace-passes` would print
 * for it goes to `line` (no trailing newline), on the calling thread, and to no other context's trace: two contexts
 * in one process keep separate traces. VKSKY_TRACE_BARRIERS: pass, commands, barrier and batch lines;
 * VKSKY_TRACE_PASSES: the pass lines alone. `what` 0 or `line` NULL turns it off. */
typedef enum vksky_trace_bits {
    VKSKY_TRACE_BARRIERS = 1u << 0,
    VKSKY_TRACE_PASSES = 1u << 1
} vksky_trace_bits;
typedef void (*vksky_trace_fn)(void *user, const char *line);
VKSKY_API vksky_result vksky_context_set_trace(vksky_context *context, uint32_t what, vksky_trace_fn line,
                                               void *user);

/* ---- Scenes: values ------------------------------------------------------------------------------------------ */

/* Earth as in Hillaire 2020 Table 1, the sun at 20 degrees. */
VKSKY_API vksky_result vksky_scene_create_earth(vksky_scene **out);
/* A scene by file (scene JSON, or an EXR written by vksky: its vksky:scene header) or by the name of a shipped
 * scene ("mars", "hazy", ... as `vksky --list-scenes` prints). Errors: VKSKY_ERROR_IO, VKSKY_ERROR_PARSE (the
 * message callback, if `message` is not NULL, gets the same line the CLI prints). */
VKSKY_API vksky_result vksky_scene_load(const char *path_or_name, vksky_message_fn message, void *message_user,
                                        vksky_scene **out);
/* The scene of a command line (`vksky` flags, a --scene file under them, as `vksky --render` would render it): the
 * medium, the sun, the units, the camera's altitude and view, exposure, tone map, dither, bloom settings and the
 * quality the flags chose (a renderer created with desc.quality "scene" takes it as it is). argv[0] is the program's
 * name. A bad flag: VKSKY_ERROR_INVALID_ARGUMENT with the command line's own one-line message to `message`. */
VKSKY_API vksky_result vksky_scene_from_args(int argc, char *const *argv, vksky_message_fn message,
                                             void *message_user, vksky_scene **out);
/* A frame of a command line's sequence (ABI 2): for a scene of vksky_scene_from_args whose command line animates
 * (`--animate FLAG=FROM:TO`), the animated flags `flags[k]` ("--sun-elevation", ...; "--time" in decimal hours) set
 * to `values[k]` over the flags and scene file as that command line read them, then everything derived from them
 * derived again (a date's sun, density scales, exposure units): the scene the same command line with those values
 * gives. Numbers, not text: nothing parsed again, no file read. A flag the command line does not animate:
 * VKSKY_ERROR_INVALID_ARGUMENT (message names it). vksky_scene_from_args of an animated command line chooses a
 * quality chosen by the scene (auto, --max-error) once for every frame, as the command line's sequence does. */
VKSKY_API vksky_result vksky_scene_set_values(vksky_scene *scene, uint32_t count, const char *const *flags,
                                              const double *values, vksky_message_fn message, void *message_user);
/* F5 (the window's; ABI 2): a scene of vksky_scene_from_args whose command line names --scene (and animates nothing)
 * gets its scene file read again, as it is on disk now, and the command line's other flags applied over it again as
 * the values vksky_scene_from_args parsed (nothing of the command line parsed again: its strings, which the scene
 * points to, must outlive it): a flag still wins over the file's field. A file that no longer loads: VKSKY_ERROR_IO or
 * VKSKY_ERROR_PARSE (the loader's line to `message`), the scene as it was. vksky_renderer_set_scene applies it. */
VKSKY_API vksky_result vksky_scene_reload(vksky_scene *scene, vksky_message_fn message, void *message_user);
VKSKY_API vksky_result vksky_scene_copy(const vksky_scene *scene, vksky_scene **out);
VKSKY_API void vksky_scene_destroy(vksky_scene *scene);
/* The sun's direction: azimuth from north (the host world's -Z with +Y up) towards east (+X), elevation above the
 * horizon. */
VKSKY_API vksky_result vksky_scene_set_sun(vksky_scene *scene, double azimuth_deg, double elevation_deg);
VKSKY_API void vksky_scene_get_sun(const vksky_scene *scene, double *azimuth_deg, double *elevation_deg);
VKSKY_API double vksky_scene_ground_radius_m(const vksky_scene *scene);
VKSKY_API double vksky_scene_atmosphere_top_m(const vksky_scene *scene);
/* The sun's illuminance at the top of the atmosphere in the scene's units (lux with VKSKY_UNITS_PHOTOMETRIC). */
VKSKY_API double vksky_scene_sun_illuminance(const vksky_scene *scene);

/* ---- Spectral frames (ABI 3) ----------------------------------------------------------------------------------
 * The command line's --spectral N as values (docs/spectral.md): N wavelengths, the centres of N bins of equal width
 * over 360-830 nm, rendered `per_pass` at a time (3, or 4 with the four-wide build) as the channels of an ordinary
 * frame. Group g of a scene is a scene of its own whose medium is the scene's spectral medium (its RGB coefficients
 * as laws of the wavelength, or its file's "spectral" section) at the group's wavelengths, each channel's sun the
 * scene's sun luminance, the ground's albedo the RGB albedo's law there. A host makes one renderer per group (each
 * keeps its LUTs: moving the sun with vksky_scene_set_sun on the group scenes recomputes what moving it in RGB does),
 * reads back each group's scene-linear image (vksky_readback_config) and sums, pixel by pixel, channel c's value
 * times xyz_weights[c] into CIE XYZ; vksky_spectral_xyz_to_rec709 turns the sum into linear Rec.709 (D65) in the RGB
 * image's units (negative out of Rec.709's gamut). A channel past the last wavelength repeats it with weight 0.
 * A renderer created with a group scene of four a pass is the four-wide build (no bloom; the readback's alpha is the
 * fourth wavelength) and takes only such scenes in vksky_renderer_set_scene; one of three a pass, or RGB, takes none of
 * four. A group scene is not split again (VKSKY_ERROR_INVALID_ARGUMENT); after a change of the scene's medium derive
 * its groups again. */
#define VKSKY_SPECTRAL_MIN 3u
#define VKSKY_SPECTRAL_MAX 48u
/* Groups of `per_pass` (3 or 4) for `wavelengths` (VKSKY_SPECTRAL_MIN..MAX); 0 for values out of range. */
VKSKY_API uint32_t vksky_spectral_group_count(uint32_t wavelengths, uint32_t per_pass);
/* Group `group` of the scene as a new scene (*group_scene, destroyed by the host), each channel's XYZ per unit of its
 * image in xyz_weights[c] (channels past per_pass: 0) and its wavelength in nm[c] (NULL: not wanted; 0 past
 * per_pass). */
VKSKY_API vksky_result vksky_scene_spectral_group(const vksky_scene *scene, uint32_t wavelengths, uint32_t per_pass,
                                                  uint32_t group, vksky_scene **group_scene,
                                                  double xyz_weights[4][3], double nm[4]);
/* What a group scene's channel renders (1/km at density 1; the albedo): for hosts and tests. Not a group scene, or a
 * channel past its per_pass: VKSKY_ERROR_INVALID_ARGUMENT. */
typedef struct vksky_spectral_coefficients {
    double rayleigh_scattering, mie_scattering, mie_absorption, ozone_absorption;
    double ground_albedo;
} vksky_spectral_coefficients;
VKSKY_API vksky_result vksky_scene_spectral_coefficients(const vksky_scene *scene, uint32_t channel,
                                                         vksky_spectral_coefficients *out);
/* CIE 1931 XYZ to linear Rec.709 / sRGB primaries (D65), the matrix the command line's spectral frames use. */
VKSKY_API void vksky_spectral_xyz_to_rec709(const double xyz[3], double rgb[3]);

/* The LUT cache (ABI 2): a directory where vksky keeps the LUTs that depend only on the medium (transmittance,
 * multi-scattering, a lit ground's irradiance), keyed by the medium, the LUT sizes, the build and the device, so that
 * a renderer of a medium seen before uploads them instead of computing them (docs/performance.md). NULL: none (the
 * default). Set it before the first renderer. Files are written only by vksky_renderer_store_luts. */
VKSKY_API vksky_result vksky_context_set_cache_directory(vksky_context *context, const char *directory);

/* ---- Renderers ------------------------------------------------------------------------------------------------ */

typedef enum vksky_output {
    /* The whole frame of the command-line tool: sky, sun disc, bloom, exposure, tone map, dither, written to the
     * host's 8-bit colour image (a swapchain image, UNORM or SRGB). */
    VKSKY_OUTPUT_DISPLAY = 0,
    /* Scene-linear: the sky written behind the host's geometry (where its depth is the far plane) and the aerial
     * perspective applied to the geometry (colour x transmittance + in-scattering), in the host's HDR colour image
     * (RGBA16F or RGBA32F, storage-capable); the host tone-maps. */
    VKSKY_OUTPUT_SCENE_LINEAR = 1,
    /* No image written: the LUTs only, for the host's own shaders (vksky_get_luts, include/vksky_luts.glsl). */
    VKSKY_OUTPUT_LUTS_ONLY = 2
} vksky_output;

typedef enum vksky_units {
    VKSKY_UNITS_PHOTOMETRIC = 0,   /* cd/m2 times vksky_frame.light_scale; the sun from the solar spectrum */
    VKSKY_UNITS_RELATIVE = 1       /* the lesson's: the sun 20, 20, 20 */
} vksky_units;

typedef struct vksky_renderer_desc {
    uint32_t abi_version;          /* VKSKY_ABI_VERSION */
    const void *next;              /* NULL, or a chain of extension structs (below: vksky_quality_config) */
    vksky_output output;
    uint32_t width, height;        /* the host image's size (ignored for LUTS_ONLY) */
    VkFormat target_format;        /* the host colour image's format */
    /* Quality: a preset by name ("low", "medium", "high", "ultra", "cpu", "auto"; NULL: "auto" for this device), or
     * with max_error > 0 the cheapest measured configuration whose mean error is within it (`--max-error`);
     * "scene": the quality a vksky_scene_from_args scene's flags chose, knob by knob. */
    const char *quality;
    double max_error;
    bool bloom;                    /* DISPLAY only */
    vksky_units units;
    const vksky_scene *scene;      /* NULL: Earth. Copied: the host may destroy it after the call. */
} vksky_renderer_desc;

VKSKY_API vksky_result vksky_renderer_create(vksky_context *context, const vksky_renderer_desc *desc,
                                             vksky_renderer **out);

/* ---- Extension structs ------------------------------------------------------------------------------------------
 * As Vulkan's pNext chains: each extension struct begins with its type and a `next` pointer, and is chained from the
 * `next` of the struct it extends. A type this library does not know, or one chained where it does not belong, is
 * refused (VKSKY_ERROR_INVALID_ARGUMENT, the message names it) rather than ignored: a host built against a newer
 * header learns at once that a setting it asked for is not applied. New settings arrive as new types; the layout of
 * an existing type never changes without a VKSKY_ABI_VERSION bump. */
typedef enum vksky_structure_type {
    VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG = 1,   /* vksky_quality_config, from vksky_renderer_desc.next */
    VKSKY_STRUCTURE_TYPE_READBACK_CONFIG = 2,  /* vksky_readback_config, from vksky_renderer_desc.next */
    VKSKY_STRUCTURE_TYPE_FRAME_VIEW = 3,       /* vksky_frame_view, from vksky_frame.next */
    VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE = 4,    /* vksky_auto_exposure, from vksky_frame.next */
    VKSKY_STRUCTURE_TYPE_FRAME_BAND = 5,       /* vksky_frame_band, from vksky_frame.next */
    VKSKY_STRUCTURE_TYPE_READBACK_TARGET = 16, /* vksky_readback_target, from vksky_frame.next (sequences) */
    /* ABI 3, from vksky_frame.next (an interactive window's frames): */
    VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY = 17,   /* vksky_frame_display */
    VKSKY_STRUCTURE_TYPE_FRAME_PLACE = 18,     /* vksky_frame_place */
    VKSKY_STRUCTURE_TYPE_FRAME_TIMER = 19,     /* vksky_frame_timer */
    VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE = 20,   /* vksky_frame_capture */
    VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN = 21, /* vksky_frame_swapchain */
    VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG = 22,  /* ABI 4: vksky_display_config, from vksky_renderer_desc.next */
    VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM = 23   /* ABI 4: vksky_frame_spectral_sum, from vksky_frame.next */
} vksky_structure_type;
typedef struct vksky_chain {   /* the head every extension struct starts with: to walk a chain */
    vksky_structure_type type;
    const void *next;
} vksky_chain;

typedef enum vksky_sky_mode {
    VKSKY_SKY_MODE_MARCH = 0,      /* a march per pixel */
    VKSKY_SKY_MODE_SKYVIEW = 1,    /* the sky-view LUT looked up */
    VKSKY_SKY_MODE_AUTO = 2        /* the LUT inside the atmosphere, the march from space */
} vksky_sky_mode;
typedef enum vksky_sky_pass {
    VKSKY_SKY_PASS_FRAGMENT = 0,   /* a full-screen draw */
    VKSKY_SKY_PASS_COMPUTE = 1,    /* a compute dispatch */
    VKSKY_SKY_PASS_AUTO = 2        /* fragment on a CPU device, compute on a GPU */
} vksky_sky_pass;

/* The quality, knob by knob (the command line's --steps, --sky-mode, ... flags; docs/quality.md): chained from
 * vksky_renderer_desc.next it replaces desc.quality and desc.max_error. vksky_quality_config_preset fills one from a
 * preset, for a host to change a knob of. Ranges are the command line's; a value outside is refused. */
typedef struct vksky_quality_config {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_QUALITY_CONFIG */
    const void *next;
    vksky_sky_mode sky_mode;
    vksky_sky_pass sky_pass;
    uint32_t view_steps;           /* 1..4096: view march steps per pixel (the least, with view_max_steps) */
    uint32_t view_max_steps;       /* 0: view_steps fixed; else view_steps..4096, more steps as the path grows */
    double step_distribution;      /* 1..4: steps end at t_max (i/N)^P */
    double sample_offset;          /* 0..1: the sample's place within its step */
    uint32_t skyview_width, skyview_height;   /* 2..4096 each */
    uint32_t skyview_steps;        /* 1..1024 */
    uint32_t transmittance_width, transmittance_height;   /* 2..4096 each */
    uint32_t transmittance_steps;  /* 1..4096 */
    uint32_t multiscatter_size;    /* 2..1024 */
    uint32_t multiscatter_sqrt_dirs;   /* 1..64: the square root of the sphere directions per texel */
    uint32_t multiscatter_steps;   /* 1..4096 */
    bool lut_f32;                  /* 32-bit float LUTs (else 16-bit) */
    double render_scale;           /* 0.1..1: the sky at this fraction of the output size */
    uint32_t bloom_mips;           /* 1..8 */
    bool bloom_quarter;            /* the bloom chain from a quarter-size mip 0 (else half) */
} vksky_quality_config;
/* A preset's knobs ("low", "medium", "high", "ultra", "lesson", "cpu"; not "auto", which depends on the device and
 * the view): VKSKY_ERROR_INVALID_ARGUMENT for another name. */
VKSKY_API vksky_result vksky_quality_config_preset(const char *preset, vksky_quality_config *out);
/* DISPLAY into vksky's own images, read back (the command-line tool's `--render`): chained from
 * vksky_renderer_desc.next (output DISPLAY, target_format R8G8B8A8_SRGB), the renderer keeps its own 8-bit display
 * image and a scene-linear AOV of it (RGBA16F: the sky and bloom before exposure and tone map, what an EXR stores
 * and what auto exposure meters), and each vksky_record copies both into host-visible buffers of the renderer's,
 * left available to HOST_READ (the frame spine's readback step: its barriers traced as the CLI's). frame.color is
 * then unused (zeroed). vksky_renderer_get_readback gives the pixels once the host waited for the command buffer. */
typedef struct vksky_readback_config {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_READBACK_CONFIG */
    const void *next;
} vksky_readback_config;
typedef struct vksky_readback {
    const uint16_t *linear_rgba16f;   /* width x height x 4 halfs, row 0 at the top, scene-linear in the HDR image's
                                         units (VKSKY_UNITS_PHOTOMETRIC: cd/m2 times the scene's light scale, which
                                         keeps the sun within half floats; the CLI's EXR divides it out) */
    const uint8_t *display_rgba8;     /* width x height x 4 bytes, sRGB-encoded, tone-mapped */
    uint32_t width, height;
} vksky_readback;
/* The pixels of the last frame recorded into a command buffer the host has waited for (non-coherent memory is
 * invalidated here); valid until the next vksky_record. VKSKY_ERROR_INVALID_ARGUMENT without a readback config. */
VKSKY_API vksky_result vksky_renderer_get_readback(vksky_renderer *renderer, vksky_readback *out);
/* Readback slots (ABI 2, a host's readback ring: the command line's sequences). A renderer with a readback config has
 * one pair of readback buffers (slot 0); vksky_renderer_set_readback_slots(renderer, n) gives it n pairs (1..
 * VKSKY_READBACK_SLOTS_MAX, no command buffer of it pending), and a frame chaining a vksky_readback_target copies into
 * pair `slot` (the frame spine's readback step as always: its barriers traced as the CLI's). The ring stays the
 * host's: which slot a frame uses, its command buffers, its fences, its waits. After the host waited for that frame,
 * vksky_renderer_get_readback_slot gives the slot's pixels; it may run on another thread than the one recording the
 * next frames into other slots (it only invalidates and reads that slot's memory): the one exception to the rule
 * that calls on a renderer do not overlap. */
#define VKSKY_READBACK_SLOTS_MAX 4u
typedef struct vksky_readback_target {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_READBACK_TARGET */
    const void *next;
    uint32_t slot;                 /* < the renderer's readback slots */
    /* An earlier frame's copies into this slot were recorded into the same command buffer (frames back to back, no
     * fence and host read between them: the command line's VKSKY_FRAMES test loop): this frame's copies rewrite what
     * those wrote, so vksky records the write-after-write barrier between them (frames.readback_*). */
    bool follows_frame;
} vksky_readback_target;
VKSKY_API vksky_result vksky_renderer_set_readback_slots(vksky_renderer *renderer, uint32_t count);
VKSKY_API vksky_result vksky_renderer_get_readback_slot(vksky_renderer *renderer, uint32_t slot, vksky_readback *out);
/* The host must know no command buffer recorded for it is pending. NULL is ignored. */
VKSKY_API void vksky_renderer_destroy(vksky_renderer *renderer);
/* A new scene (copied). The LUTs are rebuilt by the next vksky_record if the medium changed; the pipelines only if
 * the scene needs another variant (species present, multi-scattering, ground, phase model). No command buffer
 * recorded for the renderer may be pending. */
VKSKY_API vksky_result vksky_renderer_set_scene(vksky_renderer *renderer, const vksky_scene *scene);
/* Would vksky_renderer_set_scene(renderer, scene) rewrite what recorded frames read (the uniform block, the LUTs'
 * inputs, the pipelines)? A host with frames in flight waits for them first only then (the command line's ring:
 * `ring.drain`); a scene that changes only what each frame records (the sun's place, the view) needs no wait. */
VKSKY_API bool vksky_renderer_scene_changes(const vksky_renderer *renderer, const vksky_scene *scene);
/* Will the next vksky_record compute the LUTs (none built yet, or the medium changed since)? (ABI 2: the command
 * line's "LUTs computed / reused" per frame.) */
VKSKY_API bool vksky_renderer_luts_stale(const vksky_renderer *renderer);
VKSKY_API vksky_result vksky_renderer_resize(vksky_renderer *renderer, uint32_t width, uint32_t height);

/* After the host waited for the frame that computed the LUTs on a cache miss (vksky_context_set_cache_directory):
 * reads them back and writes the cache file. It submits a command buffer of its own to the context's queue and waits
 * for it (the host must not use that queue on another thread meanwhile). Nothing to do (no directory, a hit, stored
 * already): VKSKY_SUCCESS at once. */
VKSKY_API vksky_result vksky_renderer_store_luts(vksky_renderer *renderer);

/* ---- Frames --------------------------------------------------------------------------------------------------- */

/* How an image is used just before vksky's first access (what vksky waits for) or just after its last (what vksky
 * makes its writes available to): the host's stage, access and layout. layout UNDEFINED in `before`: the contents
 * are not needed (DISPLAY overwrites every pixel). */
typedef struct vksky_image_use {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
} vksky_image_use;

typedef struct vksky_image {
    VkImage image;
    VkImageView view;              /* a 2D colour (or depth) view of mip 0, layer 0 */
    VkFormat format;
    VkExtent2D extent;
    vksky_image_use before, after;
} vksky_image;

/* The host's camera. The world: metres, +Y up, the world origin origin_altitude_m above the ground (the planet's
 * centre straight below it), so the ground is the sphere through y = -origin_altitude_m. Matrices are column-major as GLSL reads them: view (world -> eye) and
 * projection (eye -> Vulkan clip space: y down, depth 0..1; reversed depth is detected from the matrix). */
typedef struct vksky_camera {
    double position_m[3];          /* world */
    double origin_altitude_m;      /* the world origin's altitude above the ground */
    double view[16];
    double projection[16];
} vksky_camera;

/* The matrices vksky's command-line camera uses: yaw (0: north, -Z; 90: east, +X) and pitch in degrees, the vertical
 * field of view, width / height, the near plane (far at infinity, reversed depth: 1 at near, 0 at infinity). */
VKSKY_API void vksky_camera_look(vksky_camera *camera, double yaw_deg, double pitch_deg, double vertical_fov_deg,
                                 double aspect, double near_m);

/* The view as the command line gives it (`--yaw`, `--pitch`, `--fov`, a perspective frame), chained from
 * vksky_frame.next instead of frame.camera's matrices: the rays the command-line tool computes, bit for bit (rays
 * from matrices match them only to float rounding). The camera's altitude is the scene's (vksky_scene_from_args:
 * `--altitude`). DISPLAY only. */
typedef struct vksky_frame_view {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_VIEW */
    const void *next;
    double yaw_deg;                /* 0: north; 90: east */
    double pitch_deg;              /* -90..90 */
    double fov_deg;                /* the vertical field of view, 1..170 */
} vksky_frame_view;

/* Auto exposure, chained from vksky_frame.next (DISPLAY only; frame.exposure is then ignored): the GPU meters this
 * frame's scene-linear image (the log-average luminance of the sky's pixels, or of every pixel over a lit ground) and
 * the same frame's tone map reads the result, EV100 = log2(L 100 / 12.5) (docs/units.md). No CPU round trip. `slot`
 * (< VKSKY_AUTO_EXPOSURE_SLOTS) is where the result is kept for vksky_renderer_get_exposure: one per frame in flight.
 * `ease` is temporal adaptation: the fraction of the way from the last metered EV100 to this frame's (0 or >= 1: none,
 * this frame's metered value). */
#define VKSKY_AUTO_EXPOSURE_SLOTS 4u
typedef struct vksky_auto_exposure {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE */
    const void *next;
    uint32_t slot;
    double ease;
} vksky_auto_exposure;

/* What the meter measured in `slot`, once the command buffer that recorded that frame completed: EV100, the
 * log-average luminance (cd/m2 in photometric units, the lesson's scale in relative ones) and the pixels counted. */
typedef struct vksky_exposure {
    double ev100;
    double log_average;
    double pixel_count;
} vksky_exposure;
VKSKY_API vksky_result vksky_renderer_get_exposure(const vksky_renderer *renderer, uint32_t slot, vksky_exposure *out);

/* The projection of an image (the command line's --projection; the names differ from the shaders' VKSKY_PROJECTION_*,
 * which are the same numbers). */
typedef enum vksky_projection {
    VKSKY_PROJECTION_TYPE_PERSPECTIVE = 0,   /* the view's (vksky_frame_view) */
    VKSKY_PROJECTION_TYPE_EQUIRECT = 1, /* latitude-longitude, W x W/2 */
    VKSKY_PROJECTION_TYPE_CUBE = 2,     /* six faces of W x W stacked vertically (+X, -X, +Y, -Y, +Z, -Z: OpenEXR's) */
    VKSKY_PROJECTION_TYPE_FISHEYE = 3   /* the upper hemisphere, equidistant, zenith at the centre, north up, east left, W x W */
} vksky_projection;

/* A band of a larger image, or an environment map, chained from vksky_frame.next (DISPLAY: with a readback config,
 * the command line's banded renders; or into the host's image, as `vksky --bench` of a map does): the frame is rows first_row .. first_row + height - 1 of a whole image of
 * whole_height rows (the renderer's width and height are the band's; whole_width must be the renderer's width), in
 * `projection`, so each pixel gets the direction it has in the whole image and the bands put together equal one
 * frame of the whole image. first_row may be negative and a band may reach below the image: such rows are drawn only
 * as the tone map's neighbours (the horizon taps) and the host drops them; the tone map clamps its taps to the whole
 * image. A perspective band takes its view from a vksky_frame_view (required); the other projections are fixed to
 * the world (no view, no camera). The renderer must draw at full size (render_scale 1: a band's rows are its own).
 * With vksky_auto_exposure, the meter counts only the frame's rows meter_first_row .. meter_first_row + meter_rows - 1
 * (the band's own: no row counted twice across bands; meter_rows 0: every row) and vksky_renderer_get_exposure gives
 * that band's log-average and pixel count: the whole image's log-average is exp(sum of count ln(log_average) / sum of
 * count) over its bands, which is the one-frame meter's (docs/library.md). */
typedef struct vksky_frame_band {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_BAND */
    const void *next;
    vksky_projection projection;
    uint32_t whole_width, whole_height;   /* the whole image: whole_width = the renderer's width; 1..1048576 rows */
    int32_t first_row;             /* the whole image's row of the frame's row 0 (-height .. whole_height) */
    uint32_t meter_first_row, meter_rows;   /* within the frame's rows */
} vksky_frame_band;

typedef struct vksky_frame {
    const void *next;              /* NULL, or a chain of frame extension structs (vksky_frame_view,
                                      vksky_auto_exposure, vksky_frame_band) */
    const vksky_camera *camera;
    /* The exposure: EV100 with VKSKY_UNITS_PHOTOMETRIC (DISPLAY: the tone map's; SCENE_LINEAR: none applied), stops
     * with RELATIVE. */
    double exposure;
    vksky_image color;             /* DISPLAY: the 8-bit image; SCENE_LINEAR: the HDR image holding the geometry */
    const vksky_image *depth;      /* SCENE_LINEAR: the host's depth (sampled; NULL: sky in every pixel) */
    bool force_luts;               /* rebuild the LUTs even if their inputs did not change (benchmarks) */
} vksky_frame;

/* Records into `cmd` (recording, outside a render pass, on the context's queue family): the LUT passes when the
 * scene's medium changed since the LUTs were last built, then the output's passes, with every barrier between them
 * and on the host's images (from color.before / depth.before to vksky's uses and back to .after). No allocation,
 * no submission, no wait. LUTS_ONLY: the LUTs only, left readable by compute and fragment shaders. */
VKSKY_API vksky_result vksky_record(vksky_renderer *renderer, VkCommandBuffer cmd, const vksky_frame *frame);

/* LUT-only mode (any output): the LUT views and the sampler to read them with, in the layout
 * SHADER_READ_ONLY_OPTIMAL after vksky_record, readable by compute and fragment shaders; the uniform block's values
 * the host's shaders need (include/vksky_luts.glsl declares the functions that sample them). */
typedef struct vksky_luts {
    VkImageView transmittance, multiscatter, skyview;
    VkSampler sampler;             /* linear, clamp to edge */
    float bottom_radius_km, top_radius_km;
    float sun_direction[3];        /* in vksky's local frame of the last recorded frame */
    float sun_illuminance[3];
    /* The barrier's destination side a host uses to wait for the LUTs in its own passes: */
    VkPipelineStageFlags2 ready_stage;
    VkAccessFlags2 ready_access;
} vksky_luts;
VKSKY_API vksky_result vksky_get_luts(const vksky_renderer *renderer, vksky_luts *out);

/* GPU time per pass of the renderer's last recorded frame (timestamps written into the host's command buffer by
 * vksky_record). Call it after that command buffer completed (it waits for the results otherwise) and before the
 * next vksky_record. Fills up to `capacity` entries (names are the passes' as the trace prints them, valid until
 * the renderer is destroyed) and sets *count to the number of timed passes; a pass that runs several times (the
 * bloom chain's) has one entry per run. VKSKY_ERROR_UNSUPPORTED: the queue family has no timestamps. */
typedef struct vksky_pass_timing {
    const char *name;
    double gpu_ms;
} vksky_pass_timing;
VKSKY_API vksky_result vksky_renderer_get_timings(vksky_renderer *renderer, vksky_pass_timing *out, uint32_t capacity,
                                                  uint32_t *count);
/* ABI 2, the LUTs on an async compute queue: GPU time per LUT pass of the last vksky_record_luts that recorded them
 * (timestamps written into the compute command buffer, on the compute queue's own timer), read as
 * vksky_renderer_get_timings reads the frame's: after that command buffer completed, before the next
 * vksky_record_luts. VKSKY_ERROR_INVALID_ARGUMENT: the context has no compute queue; VKSKY_ERROR_UNSUPPORTED: no
 * timestamps. */
VKSKY_API vksky_result vksky_renderer_get_lut_timings(vksky_renderer *renderer, vksky_pass_timing *out,
                                                      uint32_t capacity, uint32_t *count);

/* What making the renderer cost and what its LUT cache did (ABI 2: the command line's --timings): wall milliseconds
 * spent making pipelines and resources (creation and variant rebuilds), the times the pipelines were built, and the
 * LUT cache's state after the last frame (and vksky_renderer_store_luts). The LUT and sky passes' pipelines are made
 * when a frame first records with them, and their time is the frame's, not pipelines_ms. */
typedef enum vksky_lut_cache_state {
    VKSKY_LUT_CACHE_OFF = 0,           /* no cache directory */
    VKSKY_LUT_CACHE_HIT = 1,           /* uploaded, not computed */
    VKSKY_LUT_CACHE_COMPUTED = 2,      /* computed, not stored yet (vksky_renderer_store_luts) */
    VKSKY_LUT_CACHE_STORED = 3,        /* computed and stored */
    VKSKY_LUT_CACHE_NOT_STORED = 4     /* computed, the file could not be written */
} vksky_lut_cache_state;
typedef struct vksky_renderer_stats {
    double pipelines_ms;
    uint32_t variant_builds;
    vksky_lut_cache_state lut_cache;
} vksky_renderer_stats;
VKSKY_API vksky_result vksky_renderer_get_stats(const vksky_renderer *renderer, vksky_renderer_stats *out);

/* ABI 2, the LUTs on an async compute queue (a context with a compute queue): records the LUT passes into
 * `compute_cmd` (recording, a command buffer of the compute queue's family) when the scene's medium changed since they
 * were last built, or `force`; *recorded (may be NULL) says whether it did. The next vksky_record then records no LUT
 * pass (and, with another family, first the acquire of the LUT images this call released). The host submits
 * compute_cmd signalling a timeline semaphore value v of its own, and the graphics submission holding that
 * vksky_record waits for >= v at vksky_luts.ready_stage (COMPUTE_SHADER | FRAGMENT_SHADER); the compute submission
 * holding the next vksky_record_luts must wait for the graphics submissions that sampled the LUTs (their value, at
 * COMPUTE_SHADER). No allocation, no submission, no wait. docs/library.md, docs/synchronization.md §10. */
VKSKY_API vksky_result vksky_record_luts(vksky_renderer *renderer, VkCommandBuffer compute_cmd, bool force,
                                         bool *recorded);

/* ---- ABI 3: an interactive window's frames (the command line's window is this API's host) ----------------------
 * Each is chained from vksky_frame.next, DISPLAY into the host's image (no readback config) only. */

/* The tone map's operator (the window's keys 1, 2, 3; the command line's --tonemap). */
typedef enum vksky_tonemap {
    VKSKY_TONEMAP_OPERATOR_CLAMP = 0,
    VKSKY_TONEMAP_OPERATOR_REINHARD = 1,
    VKSKY_TONEMAP_OPERATOR_ACES = 2
} vksky_tonemap;
/* This frame's tone map operator and bloom switch, instead of the scene's (the window's B key). Bloom on needs a
 * renderer created with desc.bloom (its chain allocated); off skips the chain's passes. No pipeline is rebuilt. A
 * readback renderer takes it too (its composite then has no bloom: a spectral group's frame for the host's meter). */
typedef struct vksky_frame_display {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_DISPLAY */
    const void *next;
    vksky_tonemap tonemap;
    bool bloom;
} vksky_frame_display;

/* Where the camera of a vksky_frame_view is (required beside it): its altitude above the ground and the sun in the
 * camera's local frame (azimuth 0 along the view's yaw 0), instead of the scene's. A fly camera over a round planet
 * keeps these per frame; the rays are the command line's for the same values, bit for bit. */
typedef struct vksky_frame_place {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_PLACE */
    const void *next;
    double altitude_km;            /* >= 0 */
    double sun_azimuth_deg;        /* -720..720 */
    double sun_elevation_deg;      /* -90..90 */
} vksky_frame_place;

/* GPU timers per frame in flight: this frame's pass timestamps go to timer `slot` (< VKSKY_TIMER_SLOTS, the host's
 * frame slot), so frame N's times can be read (vksky_renderer_get_slot_timings) after frame N+1 was recorded into
 * another slot. A slot's query pool is made the first time a frame names it. */
#define VKSKY_TIMER_SLOTS 4u
typedef struct vksky_frame_timer {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_TIMER */
    const void *next;
    uint32_t slot;
} vksky_frame_timer;
/* The passes' GPU times of the last frame recorded with timer `slot`, once the host waited for its command buffer
 * (as vksky_renderer_get_timings). *count 0: no frame recorded with that slot since the last read, or a read before
 * (each frame's times are read once). */
VKSKY_API vksky_result vksky_renderer_get_slot_timings(vksky_renderer *renderer, uint32_t slot, vksky_pass_timing *out,
                                                       uint32_t capacity, uint32_t *count);

/* A screenshot: after the tone map, this frame's colour image (frame.color: 4 bytes a pixel, its format's byte
 * order, usage TRANSFER_SRC) is copied into the renderer's capture buffer (made at the first such frame, width x
 * height x 4 bytes), made available to HOST_READ; then the image goes to color.after (or presentation). Traced as
 * display.write_to_capture and capture.to_host. vksky_renderer_get_capture gives the bytes after the host waited. */
typedef struct vksky_frame_capture {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_CAPTURE */
    const void *next;
} vksky_frame_capture;
/* The last captured frame's bytes (display_rgba8: the colour image's bytes as they are, e.g. BGRA for a B8G8R8A8
 * swapchain; linear_rgba16f NULL); valid until the next captured frame or a resize. VKSKY_ERROR_INVALID_ARGUMENT:
 * nothing captured. */
VKSKY_API vksky_result vksky_renderer_get_capture(vksky_renderer *renderer, vksky_readback *out);

/* frame.color is a swapchain image: acquired before (the host's submission waits for the acquire semaphore at
 * COLOR_ATTACHMENT_OUTPUT, the image's contents not needed) and presented after (the host's submission signals its
 * semaphore at ALL_COMMANDS): color.before and color.after are ignored, the layouts are UNDEFINED and
 * PRESENT_SRC_KHR, and the barriers carry the window's names, display.to_attachment and display.to_present
 * (docs/synchronization.md), instead of host.color.*. */
typedef struct vksky_frame_swapchain {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_SWAPCHAIN */
    const void *next;
} vksky_frame_swapchain;

/* ---- ABI 4: the tone map's path into the host's image (output DISPLAY) --------------------------------------------
 * The tone map writes frame.color either as a colour attachment (a fragment pass: any DISPLAY format, sRGB included)
 * or as a storage image (a compute dispatch after the compute bloom chain, fused with its last upsample: the sRGB
 * curve encoded in the shader; the same bytes within 1/255). Only the host knows its images' usage, so a renderer
 * created without a vksky_display_config takes the fragment path, as before. With one (chained from
 * vksky_renderer_desc.next, output DISPLAY, no readback config):
 *   AUTO: compute when target_usage has VK_IMAGE_USAGE_STORAGE_BIT, target_format is R8G8B8A8_UNORM with the
 *         device's STORAGE_IMAGE feature, and the post chain is compute (a GPU; a CPU implementation such as lavapipe
 *         keeps the fragment chain); else fragment. An sRGB format (not storage-capable on most devices) is fragment.
 *   COMPUTE: the compute path, the compute post chain included, on any device; VKSKY_ERROR_UNSUPPORTED (with a
 *         message) when the format or usage cannot be a storage image.
 *   FRAGMENT: the fragment path always.
 * On the compute path the host's image goes from color.before to GENERAL (COMPUTE_SHADER, SHADER_STORAGE_WRITE) and
 * from there to color.after, traced as host.color.to_compute_tonemap and host.color.compute_to_after (docs/library.md,
 * docs/synchronization.md). The renderer keeps one descriptor set per host view it has written (8, the least
 * recently used rewritten for a new view): a command buffer of one of the last 7 views may be pending. A frame with
 * a vksky_frame_capture or a vksky_frame_swapchain takes the fragment path. */
typedef enum vksky_tonemap_path {
    VKSKY_TONEMAP_PATH_AUTO = 0,
    VKSKY_TONEMAP_PATH_FRAGMENT = 1,
    VKSKY_TONEMAP_PATH_COMPUTE = 2
} vksky_tonemap_path;
typedef struct vksky_display_config {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG */
    const void *next;
    VkImageUsageFlags target_usage;   /* the usage the host's colour images were created with */
    vksky_tonemap_path tonemap_path;
} vksky_display_config;
/* The path the renderer's frames into the host's image take: FRAGMENT or COMPUTE (never AUTO); FRAGMENT for a
 * renderer of another output or with a readback config. */
VKSKY_API vksky_tonemap_path vksky_renderer_get_tonemap_path(const vksky_renderer *renderer);
/* ---- ABI 4: compositing a render (the command line's --composite and --aovs; docs/library.md, "Compositing a
 * render") -----------------------------------------------------------------------------------------------------
 * The atmosphere applied to an image the host rendered (its beauty and world position per pixel), with its layers:
 * the composite, the sky, the sun disc, the transmittance and the Rayleigh and Mie in-scattering. A composite pass is
 * made over a renderer (its LUTs, its scene's medium and sun; the renderer must outlive it; an RGB scene's, or a
 * spectral group's of three a pass, whose layers then hold its three wavelengths for the host to sum, as the command
 * line's --composite --spectral N does: docs/aerial_perspective.md "Spectral colour") for bands of `width` x
 * `rows` pixels; an image of any height is composited band by band. Per band the host writes the inputs into a slot's
 * host-visible buffer, records the frame into its own command buffer (LUTs when stale, the upload, the pass, the copy
 * back: every barrier vksky's, named in docs/synchronization.md), submits it, waits, and reads the slot's layers. Two
 * slots let it fill band k+1 while the GPU composites band k: a slot is the host's again once the command buffer that
 * last recorded it has completed. */
typedef struct vksky_composite vksky_composite;
#define VKSKY_COMPOSITE_SLOTS_MAX 2u
#define VKSKY_COMPOSITE_LAYERS 6u   /* 0 composite (RGBA), 1 sky, 2 sun disc, 3 transmittance, 4 Rayleigh, 5 Mie */

/* The rendered image's world, its camera and sun (docs/aerial_perspective.md, "Conventions"). */
typedef struct vksky_composite_view {
    double camera[3];              /* the camera's position, world units */
    double km_per_unit;            /* the world unit in km (metres: 0.001) */
    int up_axis;                   /* 1: +Y up, 2: +Z up */
    double ground_altitude_km;     /* the altitude of the plane "world up = 0" */
    bool oriented;                 /* the axes below are known (else pixels without geometry keep the beauty) */
    double forward[3], right[3], up[3];   /* the camera's axes in world coordinates (unit, right-handed) */
    double fov_y_deg;              /* vertical field of view */
    double sun_azimuth_deg, sun_elevation_deg;   /* azimuth 0: north, 90: east */
    int steps, max_steps;          /* march steps (a count growing with the path when max_steps > steps) */
    double steps_ramp_km, sample_offset, step_distribution;
    double altitude_km;            /* with VKSKY_COMPOSITE_VIEW_ALTITUDE: the camera's altitude as given */
} vksky_composite_view;
/* The axes of the command line's yaw (0 north, 90 east) and pitch, in the view's world (its up_axis); oriented. */
VKSKY_API void vksky_composite_view_orient(vksky_composite_view *view, double yaw_deg, double pitch_deg);
/* The camera's altitude in km above the scene's ground (negative: inside the planet), as vksky_composite_set_view
 * finds it: for a host's check before it makes a device. */
VKSKY_API double vksky_composite_view_altitude(const vksky_composite_view *view, const vksky_scene *scene);
/* World coordinates -> vksky's local frame (north, up, east): Z up (x, y, z) -> (y, z, x), Y up -> (-z, y, x). */
VKSKY_API void vksky_composite_world_to_local(int up_axis, const double world[3], double local[3]);

typedef struct vksky_composite_desc {
    uint32_t abi_version;          /* VKSKY_ABI_VERSION */
    const void *next;              /* NULL */
    uint32_t width, rows;          /* one band: the image's width, and rows per band (a whole image: its height) */
    uint32_t slots;                /* 0 or 1: one pair of buffers; 2: two (a host's ring of bands) */
    bool volume;                   /* camera -> point from a froxel volume (the view must be oriented), else a march
                                      per pixel */
    uint32_t volume_size[3];       /* 1..512 each: width, height, depth slices */
    double volume_range_km, volume_distribution;   /* > 0; >= 1 */
} vksky_composite_desc;
/* VKSKY_ERROR_UNSUPPORTED: the device cannot hold a band of that size (the message says its limit). */
VKSKY_API vksky_result vksky_composite_create(vksky_renderer *renderer, const vksky_composite_desc *desc,
                                              vksky_composite **out);
/* The host must know no command buffer recorded for it is pending. NULL is ignored. */
VKSKY_API void vksky_composite_destroy(vksky_composite *composite);

typedef enum vksky_composite_flags {
    VKSKY_COMPOSITE_FAST = 1u,           /* the fast defaults (docs/aerial_perspective.md "Cost") when max_steps is 0 */
    VKSKY_COMPOSITE_VIEW_ALTITUDE = 2u,  /* the camera's altitude is view.altitude_km (a sky frame's own camera) */
} vksky_composite_flags;
/* The view of the whole image of `whole_height` rows, for the frames recorded after it; *altitude_km (may be NULL):
 * the camera's altitude. VKSKY_ERROR_INVALID_ARGUMENT: the camera is inside the planet. */
VKSKY_API vksky_result vksky_composite_set_view(vksky_composite *composite, const vksky_composite_view *view,
                                               uint32_t whole_height, uint32_t flags, double *altitude_km);
/* Where the host writes a band's inputs (host-visible; the slot must be the host's): rows x width RGBA floats of the
 * beauty (premultiplied, alpha the coverage), then rows x width of the world position (xyz; w is vksky's: it marks
 * the sky tiles there when the frame is recorded), top row first. Rows past the image's last: alpha 1, position
 * NaN (nothing marched). NULL for a slot out of range. */
VKSKY_API float *vksky_composite_inputs(vksky_composite *composite, uint32_t slot);

typedef struct vksky_composite_frame {
    const void *next;              /* NULL */
    uint32_t slot;                 /* < the composite's slots: its inputs, and where its layers go */
    int32_t first_row;             /* the band's first row within the whole image (0: a whole image) */
    bool force_luts;               /* rebuild the LUTs even if their inputs did not change (benchmarks) */
    bool follows_frame;            /* another composite frame was recorded before it into the same command buffer */
} vksky_composite_frame;
/* Records the frame into `cmd` (recording, outside a render pass, on the context's queue family); reads the slot's
 * inputs now (the sky tiles). The passes' GPU times: vksky_renderer_get_timings of the composite's renderer. */
VKSKY_API vksky_result vksky_composite_record(vksky_composite *composite, VkCommandBuffer cmd,
                                             const vksky_composite_frame *frame);
/* Layer `layer` (< VKSKY_COMPOSITE_LAYERS) of the slot's last frame, once its command buffer completed: rows x width
 * RGBA floats, top row first. NULL for a slot or layer out of range. */
VKSKY_API const float *vksky_composite_layer(vksky_composite *composite, uint32_t slot, uint32_t layer);
/* ---- ABI 4: spectral groups summed on the GPU -----------------------------------------------------------------
 * A frame of --spectral N without a host sum: the groups' frames (renderers made with a group scene of
 * vksky_scene_spectral_group and a vksky_readback_config) recorded with a vksky_frame_spectral_sum chained, each adding
 * its scene-linear image times its xyz_weights into the sum's float32 accumulation image instead of copying its
 * images to its readback buffers; the frame marked `last` turns the sum into linear Rec.709 (D65,
 * vksky_spectral_xyz_to_rec709's matrix) in the sum's host-visible buffer: one readback a frame. The groups may go into
 * one command buffer (renderers of their own) or one submission each (one renderer given each group's scene in turn):
 * the barriers between the steps are vksky's (docs/synchronization.md "The spectral sum on the GPU"). */
typedef struct vksky_spectral_sum vksky_spectral_sum;
/* The sum for frames of width x height (the group renderers' size). */
VKSKY_API vksky_result vksky_spectral_sum_create(vksky_context *context, uint32_t width, uint32_t height,
                                                 vksky_spectral_sum **out);
/* No command buffer that recorded a step of it may be pending. NULL is ignored. */
VKSKY_API void vksky_spectral_sum_destroy(vksky_spectral_sum *sum);
#define VKSKY_SPECTRAL_SUM_GROUPS_MAX 17u   /* group indices 0..16: 48 wavelengths three to a pass */
typedef struct vksky_frame_spectral_sum {
    vksky_structure_type type;     /* VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM */
    const void *next;
    vksky_spectral_sum *sum;       /* of the renderer's size and context */
    uint32_t group;                /* < VKSKY_SPECTRAL_SUM_GROUPS_MAX: the group's index within the frame */
    double xyz_weights[4][3];      /* vksky_scene_spectral_group's for this group */
    bool first;                    /* the frame's first group: the sum starts from 0 */
    bool last;                     /* the frame's last group: the sum resolved into the buffer (after this one's) */
} vksky_frame_spectral_sum;
/* The last resolved frame, once the host waited for the command buffer holding its `last` step: width x height x 4
 * floats, row 0 at the top, linear Rec.709 in the group images' units (the renderer's light scale as in
 * vksky_readback.linear_rgba16f; not clamped to half floats), alpha the last group's with three wavelengths to a pass
 * (the composite's coverage where a horizon crosses a pixel), else 1. Valid until the next `last` step runs. */
VKSKY_API vksky_result vksky_spectral_sum_get(vksky_spectral_sum *sum, const float **rgba32f);

#ifdef __cplusplus
}
#endif
#endif
