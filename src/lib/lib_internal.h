/* libvksky's handles over the renderer (include/vksky.h is the contract; this is what stands behind it). The API
 * is a thin layer: a context is a gpu_context, a scene is the command line's options value after the scene loader,
 * a renderer is a sky_renderer built from them the way the CLI's headless run builds its own. */
#ifndef VKSKY_LIB_INTERNAL_H
#define VKSKY_LIB_INTERNAL_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"
#include "gpu/barrier.h"
#include "gpu/context.h"
#include "sky/frame.h"
#include "sky/host_frame.h"
#include "sky/spectral_sum.h"

struct vksky_context {
    gpu_context gpu;
    vksky_message_fn message;
    void *message_user;
    int renderers;                 /* alive: the context's destroy refuses to pull the device from under them */
    gpu_trace_sink trace;          /* vksky_context_set_trace: bound while a call on the context records */
    bool own_debug_utils;          /* vksky's own instance has VK_EXT_debug_utils (vksky_context_set_debug_utils) */
};

/* A spectral group's medium (vksky_scene_spectral_group, api_spectral.c): what the GPU reads instead of the scene's
 * RGB medium. The sun is set where the renderer lights the scene (lib_render_inputs_of): each channel the base's sun
 * luminance in the renderer's units, so that the group's image has the RGB image's magnitudes. */
typedef struct lib_spectral_group {
    uint32_t per_pass;             /* 0: an RGB scene; 3 or 4 wavelengths a pass */
    model_atmosphere medium;       /* the first three wavelengths' coefficients as the three channels */
    sky_fourth fourth;             /* per_pass 4: the fourth wavelength's (the four-wide build) */
    double ground_albedo[4];       /* the RGB albedo's law at each wavelength */
} lib_spectral_group;

struct vksky_scene {
    options o;                     /* the scene loader's result on the CLI's defaults: medium, features, sun, units */
    bool from_args;                /* vksky_scene_from_args: o holds a command line's resolved quality too */
    lib_spectral_group group;      /* ABI 3: a spectral group's scene (per_pass > 0) */
};

/* What recorded frames read of a scene (the uniform block's medium and sun, the features that pick pipelines):
 * zeroed before it is filled, so that two compare bytewise. */
typedef struct lib_render_inputs {
    model_atmosphere lit;          /* the sun in the HDR image's units */
    double sun_radius_rad;
    sky_features features;
} lib_render_inputs;

struct vksky_renderer {
    vksky_context *ctx;
    sky_renderer r;
    options o;                     /* the scene with the renderer's quality, size and units applied */
    vksky_renderer_desc desc;      /* as given (desc.scene and desc.quality not kept: they are the caller's) */
    host_frame hf;                 /* SCENE_LINEAR: the pass over the host's colour and depth (sky/host_frame.h) */
    bool readback;                 /* vksky_readback_config: DISPLAY into its own images, copied to its buffers */
    bool scene_quality;            /* made with quality "scene": a from_args scene's view settings follow set_scene */
    /* Readback slots (api_readback.c): slot 0 is the renderer's own pair; the spine copies into r.readback_* */
    uint32_t slot_count;
    gpu_buffer slot_linear[VKSKY_READBACK_SLOTS_MAX], slot_display[VKSKY_READBACK_SLOTS_MAX];
    lib_render_inputs applied;     /* what the GPU reads of the scene, as last set (vksky_renderer_scene_changes) */
    /* ABI 3 (api_window.c): the timers of frames in flight (made at a slot's first frame) and the capture buffer */
    gpu_timer timers[VKSKY_TIMER_SLOTS];
    bool timer_made[VKSKY_TIMER_SLOTS], timer_unread[VKSKY_TIMER_SLOTS];
    gpu_buffer capture;            /* size 0: none made */
    bool captured;                 /* a frame was captured since the buffer was made */
    uint32_t per_pass;             /* ABI 3: made with a spectral group's scene: 3 or 4 (the four-wide build), else 0 */
    /* vksky_display_config (api_renderer.c): the tone map's path asked for; storage_target: the host's images can be
     * the compute tone map's storage images; host_compute: this build's frames take the compute path. */
    vksky_tonemap_path tonemap_path;
    bool storage_target, host_compute;
};

/* A frame's `next` chain, each struct or NULL (lib_frame_chain). */
typedef struct lib_frame_ext {
    const vksky_frame_view *view;
    const vksky_auto_exposure *exposure;
    const vksky_frame_band *band;
    const vksky_readback_target *target;
    const vksky_frame_display *display;   /* ABI 3 */
    const vksky_frame_place *place;
    const vksky_frame_timer *timer;
    const vksky_frame_capture *capture;
    const vksky_frame_swapchain *swapchain;
    const vksky_frame_spectral_sum *spectral_sum;   /* ABI 4 */
} lib_frame_ext;

/* ABI 4 (api_spectral_sum.c): the GPU's spectral sum, and a group frame's step of it checked against the renderer. */
struct vksky_spectral_sum {
    vksky_context *ctx;
    spectral_sum s;
};
vksky_result lib_spectral_sum_step(const vksky_renderer *r, const vksky_frame_spectral_sum *e, spectral_sum_step *out);

/* The context's trace bound to this thread for the length of a call (no trace of its own: the process-wide streams
 * stay, the CLI's and the drop probe's); returns what lib_trace_end restores. */
const gpu_trace_sink *lib_trace_begin(const vksky_context *c);
void lib_trace_end(const gpu_trace_sink *was);
/* A renderer desc's `next` chain checked (types known, in place, once; the quality config's ranges): the quality
 * config in *quality, or NULL (api_extensions.c). */
vksky_result lib_renderer_chain(const vksky_context *c, const void *next, const vksky_quality_config **quality,
                                bool *readback, const vksky_display_config **display);
/* A frame's `next` chain checked (types known, in place, once): the view (vksky_frame_view), the auto exposure and
 * the band (vksky_frame_band: its ranges are the renderer's, checked by vksky_record), each or NULL. */
vksky_result lib_frame_chain(const vksky_context *c, const void *next, lib_frame_ext *ext);
/* ABI 3's window extensions (api_window.c): checked against the renderer and applied to the frame's view and target
 * (its timer, capture buffer, swapchain uses); the timers and capture buffer made at first use. */
vksky_result lib_window_check(const vksky_renderer *r, const lib_frame_ext *ext);
vksky_result lib_window_apply(vksky_renderer *r, const lib_frame_ext *ext, sky_view *v, frame_desc *f,
                              frame_target *target);
void lib_window_destroy(vksky_renderer *r, bool timers);   /* the capture buffer, and the timers (destroy) */
struct quality_config;
void lib_quality_from_config(const vksky_quality_config *q, struct quality_config *out);
/* One message line to the callback (NULL: dropped). */
void lib_message(vksky_message_fn fn, void *user, vksky_severity severity, const char *format, ...)
    __attribute__((format(printf, 4, 5)));
/* gpu_context's messages (int severity) into a context's callback. */
void lib_gpu_message(void *user, int severity, const char *text);
/* A VkResult as the API's result. */
vksky_result lib_result_from_vk(VkResult r);
/* The CLI's defaults, then (path_or_name non-NULL) a scene file loaded onto them. 0 ok, else the scene loader's
 * line in `why`. */
int lib_options_load(const char *path_or_name, options *o, char *why, size_t why_size);
/* A command line (argv[0] the program's) parsed by the CLI's own parser; as lib_options_load. */
int lib_options_parse(int argc, char *const *argv, options *o, char *why, size_t why_size);
/* Readback slots: the renderer's own pair as slot 0 (after creation); the extra pairs destroyed (before the renderer
 * is). api_readback.c. */
void lib_readback_slots_init(vksky_renderer *r);
void lib_readback_slots_destroy(vksky_renderer *r);
/* The readback pair `slot` for the next frame's copies. */
void lib_readback_select(vksky_renderer *r, uint32_t slot);
/* A scene's options as a renderer of these options would take them (set_scene), and what the GPU reads of them. */
void lib_scene_for_renderer(const vksky_renderer *r, const vksky_scene *scene, options *o);
void lib_render_inputs_of(const options *o, const lib_spectral_group *group, lib_render_inputs *out);
/* Timer t's last frame read into out (the whole frame's timings, *count of them; up to capacity written), a device
 * error reported to the context's callback: the renderer's own timer and a window slot's (api_extensions.c). */
vksky_result lib_timings_read(vksky_renderer *renderer, gpu_timer *t, vksky_pass_timing *out, uint32_t capacity,
                              uint32_t *count);
#endif
