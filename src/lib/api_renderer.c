/* Renderers: a sky_renderer built from a scene and a quality the way the CLI's headless run builds its own
 * (app/runs/headless.c), writing the host's image instead of its own (include/vksky.h). */
#include "lib/lib_internal.h"
#include "sky/submit.h"
#include "app/scene/light.h"
#include "app/cli/options.h"
#include "app/quality/quality.h"
#include <stdlib.h>
#include <string.h>

static bool format_is_display(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM ||
           f == VK_FORMAT_B8G8R8A8_SRGB;
}

/* The scene's options with the renderer's quality, size and units: what `vksky --render` would hold. */
static vksky_result renderer_options(vksky_context *c, const vksky_renderer_desc *d, const vksky_scene *from,
                                     const vksky_quality_config *explicit_quality, options *o)
{
    const options *scene = &from->o;
    *o = *scene;
    o->unresolved = NULL;   /* the scene's own (vksky_scene_set_values) */
    o->units = d->units == VKSKY_UNITS_RELATIVE ? OPTIONS_UNITS_RELATIVE : OPTIONS_UNITS_PHOTOMETRIC;
    light_finish(o);
    const quality_config *q = NULL;
    double measured = 0.0;
    unsigned classes = quality_class_bit(o->view.altitude_km, o->view.sun_elevation_deg);
    bool cpu_device = c->gpu.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    quality_config given;
    bool scene_quality = !explicit_quality && d->max_error == 0.0 && d->quality && !strcmp(d->quality, "scene");
    if (scene_quality && !from->from_args) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "quality \"scene\": only for a scene made by vksky_scene_from_args (its flags chose one)");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (scene_quality) {
        /* The command line resolved its quality already (a preset, --max-error's pick, knob flags over them). */
    } else if (explicit_quality) {   /* the host's knobs (vksky_quality_config): no preset, no pick */
        lib_quality_from_config(explicit_quality, &given);
        q = &given;
    } else if (d->max_error > 0.0) {
        q = quality_pick(d->max_error, classes, cpu_device, &measured);   /* the running device's table */
        if (!q) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "max_error %g: no measured configuration reaches it; try a larger budget or \"ultra\"",
                        d->max_error);
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
    } else if (!d->quality || !strcmp(d->quality, "auto")) {
        q = quality_auto(classes, cpu_device, &measured);
    } else {
        q = quality_preset(d->quality);
        if (!q) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "quality \"%s\": expected low, medium, high, ultra, lesson, cpu or auto", d->quality);
            return VKSKY_ERROR_INVALID_ARGUMENT;
        }
    }
    if (q) quality_apply(q, &o->view, &o->lut, &o->render_scale, &o->bloom_mips, &o->bloom_quarter);
    o->width = (int)d->width, o->height = (int)d->height;
    o->view.bloom = d->bloom && d->output == VKSKY_OUTPUT_DISPLAY;
    return VKSKY_SUCCESS;
}

static vksky_result check_desc(vksky_context *c, const vksky_renderer_desc *d)
{
    if (d->abi_version != VKSKY_ABI_VERSION) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: abi_version %u; this library is ABI %u", d->abi_version, VKSKY_ABI_VERSION);
        return VKSKY_ERROR_ABI_MISMATCH;
    }
    if (d->output != VKSKY_OUTPUT_DISPLAY && d->output != VKSKY_OUTPUT_LUTS_ONLY &&
        d->output != VKSKY_OUTPUT_SCENE_LINEAR) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR, "vksky_renderer_create: output %d is unknown",
                    (int)d->output);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    bool sized = d->output != VKSKY_OUTPUT_LUTS_ONLY;
    if (sized && (d->width == 0 || d->height == 0 || d->width > 16384 || d->height > 16384)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: size %ux%u; expected 1..16384 each", d->width, d->height);
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    uint32_t max_2d = c->gpu.props.limits.maxImageDimension2D;   /* the renderer's images are the output's size */
    if (sized && (d->width > max_2d || d->height > max_2d)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: size %ux%u; the device's maxImageDimension2D is %u", d->width, d->height,
                    max_2d);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    if (d->output == VKSKY_OUTPUT_SCENE_LINEAR) {
        /* The pass reads and writes the host's HDR image as a storage image (sky/host_frame.c). */
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(c->gpu.physical, d->target_format, &fp);
        if (!host_frame_format_supported(d->target_format) ||
            !(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT)) {
            lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                        "vksky_renderer_create: target format %d; SCENE_LINEAR writes R16G16B16A16_SFLOAT or "
                        "R32G32B32A32_SFLOAT as a storage image", (int)d->target_format);
            return VKSKY_ERROR_UNSUPPORTED;
        }
    } else if (sized && !format_is_display(d->target_format)) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: target format %d; DISPLAY writes R8G8B8A8 or B8G8R8A8, UNORM or SRGB",
                    (int)d->target_format);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    if (d->units != VKSKY_UNITS_PHOTOMETRIC && d->units != VKSKY_UNITS_RELATIVE) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (!(d->max_error >= 0.0)) return VKSKY_ERROR_INVALID_ARGUMENT;
    return VKSKY_SUCCESS;
}

/* A vksky_display_config (include/vksky.h, "The tone map's path"): its values, and whether the host's images can be
 * the compute tone map's storage images (an R8G8B8A8_UNORM image of usage STORAGE on a device that allows it). */
static vksky_result check_display_config(const vksky_context *c, const vksky_renderer_desc *d,
                                         const vksky_display_config *dc, bool readback, bool *storage_target)
{
    if ((unsigned)dc->tonemap_path > VKSKY_TONEMAP_PATH_COMPUTE || d->output != VKSKY_OUTPUT_DISPLAY || readback) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: vksky_display_config: tonemap_path %d, output %d%s; accepted tonemap_path "
                    "AUTO, FRAGMENT or COMPUTE, for output DISPLAY without a vksky_readback_config",
                    (int)dc->tonemap_path, (int)d->output, readback ? " with a readback config" : "");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(c->gpu.physical, d->target_format, &fp);
    *storage_target = d->target_format == VK_FORMAT_R8G8B8A8_UNORM && (dc->target_usage & VK_IMAGE_USAGE_STORAGE_BIT) &&
                      (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT);
    if (dc->tonemap_path == VKSKY_TONEMAP_PATH_COMPUTE && !*storage_target) {
        lib_message(c->message, c->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: vksky_display_config: tonemap_path COMPUTE with target format %d, usage "
                    "0x%x; the compute tone map writes R8G8B8A8_UNORM images of usage STORAGE (where the device allows)",
                    (int)d->target_format, (unsigned)dc->target_usage);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    return VKSKY_SUCCESS;
}

vksky_tonemap_path vksky_renderer_get_tonemap_path(const vksky_renderer *renderer)
{
    return renderer && renderer->host_compute ? VKSKY_TONEMAP_PATH_COMPUTE : VKSKY_TONEMAP_PATH_FRAGMENT;
}

/* Creates r->r for r->o; Vulkan failures come back through the trap, with everything made so far destroyed. */
static vksky_result build(vksky_renderer *r, const lib_spectral_group *group)
{
    const options *o = &r->o;
    lib_render_inputs in;   /* the sun in the HDR image's units (app/scene/light.h); a spectral group's medium */
    lib_render_inputs_of(o, group, &in);
    model_atmosphere lit = in.lit;
    sky_features features = in.features;
    /* A group of four wavelengths a pass: the four-wide build for the renderer's life (no bloom there). */
    bool spectral4 = r->per_pass == 4;
    /* LUTS_ONLY and SCENE_LINEAR need none of the frame's own images: a 1 x 1 frame the renderer never draws. */
    bool luts_only = r->desc.output != VKSKY_OUTPUT_DISPLAY;
    /* With a readback config the frame's own display image and its scene-linear composite are kept and read back
     * (the command-line tool's headless frame); else the tone map writes the host's image. */
    sky_renderer_desc rdesc = {
        .width = luts_only ? 1 : (uint32_t)o->width, .height = luts_only ? 1 : (uint32_t)o->height,
        .bloom = o->view.bloom && !spectral4, .spectral4 = spectral4, .readback = r->readback, .external_display = !luts_only && !r->readback,
        .display_format = luts_only ? VK_FORMAT_R8G8B8A8_SRGB : r->desc.target_format,
        .render_scale = o->render_scale, .lut = o->lut, .bloom_mips = (uint32_t)o->bloom_mips,
        .post_pass = o->post_pass, .bloom_downsample = o->bloom_downsample, .bloom_quarter = o->bloom_quarter,
        .atmosphere = &lit, .sun_angular_radius_rad = options_sun_radius_rad(o), .features = &features};
    /* vksky_display_config: the compute tone map into the host's storage image (COMPUTE asks for the compute post
     * chain too; AUTO takes it where the chain is compute anyway). */
    r->host_compute = !luts_only && !r->readback && r->storage_target &&
                      (r->tonemap_path == VKSKY_TONEMAP_PATH_COMPUTE ||
                       (r->tonemap_path == VKSKY_TONEMAP_PATH_AUTO &&
                        post_pass_resolve(o->post_pass, &r->ctx->gpu) == POST_PASS_COMPUTE));
    if (r->host_compute) rdesc.post_pass = POST_PASS_COMPUTE, rdesc.host_storage_tonemap = true;
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(r->ctx->message, r->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        host_frame_destroy(&r->hf, &r->r);
        sky_renderer_destroy(&r->r);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    sky_renderer_create(&r->r, &r->ctx->gpu, &rdesc);
    char err[200];
    if (r->desc.output == VKSKY_OUTPUT_SCENE_LINEAR && host_frame_create(&r->hf, &r->r, r->desc.target_format, err,
                                                                         sizeof err) != 0) {
        gpu_trap_arm(NULL);
        lib_message(r->ctx->message, r->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", err);
        sky_renderer_destroy(&r->r);
        return VKSKY_ERROR_UNSUPPORTED;
    }
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_create(vksky_context *context, const vksky_renderer_desc *desc, vksky_renderer **out)
{
    if (out) *out = NULL;
    if (!context || !desc || !out) return VKSKY_ERROR_INVALID_ARGUMENT;
    vksky_result res = check_desc(context, desc);
    const vksky_quality_config *explicit_quality = NULL;
    bool readback = false;
    const vksky_display_config *display = NULL;
    if (res == VKSKY_SUCCESS) res = lib_renderer_chain(context, desc->next, &explicit_quality, &readback, &display);
    bool storage_target = false;
    if (res == VKSKY_SUCCESS && display) res = check_display_config(context, desc, display, readback, &storage_target);
    if (res == VKSKY_SUCCESS && readback &&
        (desc->output != VKSKY_OUTPUT_DISPLAY || desc->target_format != VK_FORMAT_R8G8B8A8_SRGB)) {
        lib_message(context->message, context->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_create: vksky_readback_config: output DISPLAY and target_format "
                    "R8G8B8A8_SRGB only (the images read back are the renderer's own)");
        res = VKSKY_ERROR_INVALID_ARGUMENT;
    }
    if (res != VKSKY_SUCCESS) return res;
    vksky_renderer *r = calloc(1, sizeof *r);
    vksky_scene *earth = NULL;
    if (!r) return VKSKY_ERROR_OUT_OF_MEMORY;
    const vksky_scene *scene = desc->scene;
    if (!scene && (res = vksky_scene_create_earth(&earth)) != VKSKY_SUCCESS) {
        free(r);
        return res;
    }
    r->ctx = context;
    r->readback = readback;
    r->tonemap_path = display ? display->tonemap_path : VKSKY_TONEMAP_PATH_FRAGMENT;
    r->storage_target = storage_target;
    r->desc = *desc;
    r->desc.scene = NULL, r->desc.quality = NULL, r->desc.next = NULL;
    r->scene_quality = !explicit_quality && desc->max_error == 0.0 && desc->quality && !strcmp(desc->quality, "scene");
    res = renderer_options(context, desc, scene ? scene : earth, explicit_quality, &r->o);
    vksky_scene_destroy(earth);
    const lib_spectral_group *group = scene ? &scene->group : NULL;
    r->per_pass = group ? group->per_pass : 0;
    const gpu_trace_sink *was = lib_trace_begin(context);   /* the uploads' commands and barriers */
    if (res == VKSKY_SUCCESS) res = build(r, group);
    lib_trace_end(was);
    if (res != VKSKY_SUCCESS) {
        free(r);
        return res;
    }
    lib_readback_slots_init(r);
    lib_render_inputs_of(&r->o, group, &r->applied);
    context->renderers++;
    *out = r;
    return VKSKY_SUCCESS;
}

void vksky_renderer_destroy(vksky_renderer *renderer)
{
    if (!renderer) return;
    lib_window_destroy(renderer, true);
    lib_readback_slots_destroy(renderer);
    host_frame_destroy(&renderer->hf, &renderer->r);
    sky_renderer_destroy(&renderer->r);
    renderer->ctx->renderers--;
    free(renderer);
}

static vksky_result set_scene(vksky_renderer *renderer, const vksky_scene *scene);

vksky_result vksky_renderer_set_scene(vksky_renderer *renderer, const vksky_scene *scene)
{
    if (!renderer || !scene) return VKSKY_ERROR_INVALID_ARGUMENT;
    const gpu_trace_sink *was = lib_trace_begin(renderer->ctx);
    vksky_result res = set_scene(renderer, scene);
    lib_trace_end(was);
    return res;
}

void lib_scene_for_renderer(const vksky_renderer *r, const vksky_scene *scene, options *o)
{
    /* The scene whole (medium, features, sun, camera altitude); the renderer's quality, size and units stay. */
    const options *was = &r->o;
    *o = scene->o;
    o->unresolved = NULL;   /* the scene's own */
    sky_view view = was->view;
    if (r->scene_quality && scene->from_args) {
        /* A command line's frame (a sequence's): its view settings too (tone map, bloom strength, the march knobs
         * of the quality it chose, which is the renderer's), as that command line renders them. */
        view = o->view;
        view.bloom = was->view.bloom;
    }
    view.sun_azimuth_deg = o->view.sun_azimuth_deg, view.sun_elevation_deg = o->view.sun_elevation_deg;
    view.altitude_km = o->view.altitude_km;
    o->view = view;
    o->lut = was->lut, o->render_scale = was->render_scale, o->bloom_mips = was->bloom_mips;
    o->bloom_quarter = was->bloom_quarter, o->post_pass = was->post_pass, o->bloom_downsample = was->bloom_downsample;
    o->width = was->width, o->height = was->height, o->units = was->units;
    light_finish(o);
}

void lib_render_inputs_of(const options *o, const lib_spectral_group *group, lib_render_inputs *out)
{
    memset(out, 0, sizeof *out);
    light_render_atmosphere(o, &out->lit);
    out->sun_radius_rad = options_sun_radius_rad(o);
    out->features = options_features(o);
    if (!group || !group->per_pass) return;
    /* A spectral group: every channel's sun is the scene's sun luminance in the HDR image's units, so that the
     * group's image has the RGB image's magnitudes (half floats keep their precision at twilight); the weights of
     * vksky_scene_spectral_group divide it out again with the solar spectrum's own illuminance. */
    const double *e = out->lit.sun_illuminance;
    double sun_y = 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2];
    out->lit = group->medium;
    for (int c = 0; c < 3; ++c) {
        out->lit.sun_illuminance[c] = sun_y;
        out->features.ground_albedo[c] = group->ground_albedo[c];
    }
    if (group->per_pass == 4) {
        out->features.fourth = group->fourth;
        out->features.fourth.sun_illuminance = sun_y;
        out->features.fourth.ground_albedo = group->ground_albedo[3];
    }
}

bool vksky_renderer_scene_changes(const vksky_renderer *renderer, const vksky_scene *scene)
{
    if (!renderer || !scene) return false;
    options o;
    lib_scene_for_renderer(renderer, scene, &o);
    lib_render_inputs in;
    lib_render_inputs_of(&o, &scene->group, &in);
    return memcmp(&in, &renderer->applied, sizeof in) != 0;
}

bool vksky_renderer_luts_stale(const vksky_renderer *renderer)
{
    return renderer && sky_renderer_luts_dirty(&renderer->r);
}

static vksky_result set_scene(vksky_renderer *renderer, const vksky_scene *scene)
{
    if ((scene->group.per_pass == 4) != (renderer->per_pass == 4)) {
        /* The four-wide build is other SPIR-V and another composite, chosen at creation. */
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR,
                    "vksky_renderer_set_scene: a scene of %s on a renderer made for %s (the four-wide build is chosen "
                    "by the scene the renderer is created with)",
                    scene->group.per_pass == 4 ? "four wavelengths a pass" : "three channels a pass",
                    renderer->per_pass == 4 ? "four wavelengths a pass" : "three channels a pass");
        return VKSKY_ERROR_INVALID_ARGUMENT;
    }
    options o;
    lib_scene_for_renderer(renderer, scene, &o);
    lib_render_inputs in;
    lib_render_inputs_of(&o, &scene->group, &in);
    if (!memcmp(&in, &renderer->applied, sizeof in)) {
        /* Nothing recorded frames read changes (the sun's place and the view go into each frame's recording): no
         * write, so frames may still be pending (vksky_renderer_scene_changes). */
        renderer->o = o;
        return VKSKY_SUCCESS;
    }
    model_atmosphere lit = in.lit;
    sky_features features = in.features;
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        /* A failed pipeline rebuild leaves no usable renderer: the host destroys it. */
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    renderer->r.features = features;   /* one upload, one variant build for both */
    sky_renderer_set_atmosphere(&renderer->r, &lit, options_sun_radius_rad(&o));
    /* A new variant may bring new pipelines and LUT views: the SCENE_LINEAR pass is rebuilt over them. */
    char err[200];
    if (renderer->desc.output == VKSKY_OUTPUT_SCENE_LINEAR) {
        host_frame_destroy(&renderer->hf, &renderer->r);
        if (host_frame_create(&renderer->hf, &renderer->r, renderer->desc.target_format, err, sizeof err) != 0) {
            gpu_trap_arm(NULL);
            lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", err);
            return VKSKY_ERROR_UNSUPPORTED;
        }
    }
    gpu_trap_arm(NULL);
    renderer->o = o;
    renderer->applied = in;
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_store_luts(vksky_renderer *renderer)
{
    if (!renderer) return VKSKY_ERROR_INVALID_ARGUMENT;
    gpu_trap trap;
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    sky_renderer_store_luts(&renderer->r);   /* only after a miss; the file's own failures are one note */
    gpu_trap_arm(NULL);
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_resize(vksky_renderer *renderer, uint32_t width, uint32_t height)
{
    if (!renderer || width == 0 || height == 0 || width > 16384 || height > 16384) return VKSKY_ERROR_INVALID_ARGUMENT;
    if (renderer->desc.output == VKSKY_OUTPUT_LUTS_ONLY) return VKSKY_SUCCESS;
    if (renderer->desc.output == VKSKY_OUTPUT_SCENE_LINEAR) {
        /* The pass sizes its dispatch by the host's image: nothing of vksky's depends on the size. */
        renderer->desc.width = width, renderer->desc.height = height;
        renderer->o.width = (int)width, renderer->o.height = (int)height;
        return VKSKY_SUCCESS;
    }
    gpu_trap trap;
    const gpu_trace_sink *was = lib_trace_begin(renderer->ctx);
    if (setjmp(trap.jump)) {
        lib_trace_end(was);
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    lib_window_destroy(renderer, false);    /* the capture buffer of the old size (the timers stay) */
    lib_readback_slots_destroy(renderer);   /* new sizes: one slot again, the renderer's own (remade) */
    sky_renderer_resize(&renderer->r, width, height);
    lib_readback_slots_init(renderer);
    gpu_trap_arm(NULL);
    lib_trace_end(was);
    renderer->desc.width = width, renderer->desc.height = height;
    renderer->o.width = (int)width, renderer->o.height = (int)height;
    return VKSKY_SUCCESS;
}

vksky_result vksky_renderer_get_readback(vksky_renderer *renderer, vksky_readback *out)
{
    if (!renderer || !out || !renderer->readback) return VKSKY_ERROR_INVALID_ARGUMENT;
    sky_renderer *r = &renderer->r;
    gpu_trap trap;   /* a failing invalidate returns its error instead of ending the host's process */
    if (setjmp(trap.jump)) {
        lib_message(renderer->ctx->message, renderer->ctx->message_user, VKSKY_SEVERITY_ERROR, "%s", trap.message);
        return lib_result_from_vk(trap.result);
    }
    gpu_trap_arm(&trap);
    /* The frame's last barrier made the copies available to HOST_READ; the host waited for the command buffer;
     * on non-coherent memory the invalidate makes them visible. */
    gpu_buffer_invalidate(r->ctx, &r->readback_linear);
    gpu_buffer_invalidate(r->ctx, &r->readback_display);
    gpu_trap_arm(NULL);
    *out = (vksky_readback){.linear_rgba16f = r->readback_linear.mapped, .display_rgba8 = r->readback_display.mapped,
                            .width = r->desc.width, .height = r->desc.height};
    return VKSKY_SUCCESS;
}
