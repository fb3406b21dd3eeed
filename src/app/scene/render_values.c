/* The renderer's scene and quality values from the options (render_values.h). */
#include "app/scene/render_values.h"
#include "app/scene/light.h"
#include "app/cli/options.h"
#include "app/cli/options_tooling.h"
#include "app/quality/quality.h"
#include "app/scene/scene.h"
#include <string.h>

render_quality render_quality_of(const options *o)
{
    const sky_view *v = &o->view;
    return (render_quality){.mode = v->mode, .pass_kind = v->pass_kind, .steps = v->steps, .max_steps = v->max_steps,
                            .skyview_steps = v->skyview_steps, .steps_ramp_km = v->steps_ramp_km,
                            .sample_offset = v->sample_offset, .step_distribution = v->step_distribution,
                            .lut = o->lut, .render_scale = o->render_scale, .bloom_mips = o->bloom_mips,
                            .post_pass = o->post_pass, .bloom_downsample = o->bloom_downsample,
                            .bloom_quarter = o->bloom_quarter};
}

void render_quality_to_view(const render_quality *q, sky_view *v)
{
    v->mode = q->mode, v->pass_kind = q->pass_kind, v->steps = q->steps, v->max_steps = q->max_steps;
    v->skyview_steps = q->skyview_steps, v->steps_ramp_km = q->steps_ramp_km, v->sample_offset = q->sample_offset;
    v->step_distribution = q->step_distribution;
}

void values_of(const options *o, scene_value *scene, camera_value *camera, render_quality *quality, job_value *job)
{
    const sky_view *v = &o->view;
    if (scene) {
        *scene = (scene_value){.atmosphere = o->atmosphere, .mie_phase = o->mie_phase,
                               .sun_angular_radius_deg = o->sun_angular_radius_deg,
                               .limb_darkening = o->limb_darkening, .sun_disc = o->sun_disc,
                               .multiple_scattering = o->multiple_scattering,
                               .sun_elevation_deg = v->sun_elevation_deg, .sun_azimuth_deg = v->sun_azimuth_deg,
                               .units = o->units};
        memcpy(scene->ground_albedo, o->ground_albedo, sizeof scene->ground_albedo);
    }
    if (camera)
        *camera = (camera_value){.altitude_km = v->altitude_km, .yaw_deg = v->yaw_deg, .pitch_deg = v->pitch_deg,
                                 .fov_deg = v->fov_deg, .ground_radius_km = o->atmosphere.bottom_radius};
    if (quality) *quality = render_quality_of(o);
    if (job) {
        *job = (job_value){.output_count = o->output_count, .width = o->width, .height = o->height,
                           .projection = v->projection, .exposure_ev = v->exposure_ev,
                           .auto_exposure = o->auto_exposure, .tonemap = v->tonemap, .bloom = v->bloom,
                           .exr_type = o->exr_type, .exr_compression = o->exr_compression, .zip_level = o->zip_level,
                           .threads = o->threads, .frame_count = o->frame_count, .frame_first = o->frame_first,
                           .frame_last = o->frame_last, .skip_existing = o->skip_existing};
        memcpy(job->outputs, o->outputs, sizeof job->outputs);
    }
}

int values_load_scene(const char *path_or_name, scene_value *scene, camera_value *camera, render_quality *quality,
                      job_value *job)
{
    options o;
    options_defaults(&o);
    const char *path = options_tooling_scene_path(path_or_name);   /* a shipped scene's name -> its file */
    if (!path) return 2;
    if (scene_load(path, &o) != 0) return 2;
    values_of(&o, scene, camera, quality, job);
    return 0;
}

/* A configuration's knobs over the defaults' post chain (quality_apply: the same knobs the CLI's presets set). */
static void from_config(const quality_config *c, render_quality *out)
{
    options o;
    options_defaults(&o);
    quality_apply(c, &o.view, &o.lut, &o.render_scale, &o.bloom_mips, &o.bloom_quarter);
    *out = render_quality_of(&o);
}

int values_quality_preset(const char *name, render_quality *out)
{
    const quality_config *c = quality_preset(name);
    if (!c) return 2;
    from_config(c, out);
    return 0;
}

int values_quality_pick(double max_error, unsigned classes, bool cpu_device, render_quality *out, double *measured)
{
    const quality_config *c = quality_pick(max_error, classes, cpu_device, measured);
    if (!c) return 2;
    from_config(c, out);
    return 0;
}
