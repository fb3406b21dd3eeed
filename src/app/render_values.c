/* The renderer's scene and quality values from the options (render_values.h). */
#include "app/render_values.h"
#include "app/light.h"
#include "app/options.h"
#include <string.h>

void render_scene_of(const options *o, render_scene *out)
{
    memset(out, 0, sizeof *out);
    light_render_atmosphere(o, &out->atmosphere);
    out->sun_radius_rad = options_sun_radius_rad(o);
    out->features = options_features(o);
}

render_quality render_quality_of(const options *o)
{
    return (render_quality){.lut = o->lut, .render_scale = o->render_scale, .bloom_mips = o->bloom_mips,
                            .post_pass = o->post_pass, .bloom_downsample = o->bloom_downsample,
                            .bloom_quarter = o->bloom_quarter};
}

sky_renderer_desc render_desc(const render_quality *q, const render_scene *s)
{
    return (sky_renderer_desc){.render_scale = q->render_scale, .lut = q->lut, .bloom_mips = (uint32_t)q->bloom_mips,
                               .post_pass = q->post_pass, .bloom_downsample = q->bloom_downsample,
                               .bloom_quarter = q->bloom_quarter, .atmosphere = &s->atmosphere,
                               .sun_angular_radius_rad = s->sun_radius_rad, .features = &s->features};
}

void render_scene_set(sky_renderer *r, const render_scene *s)
{
    sky_renderer_set_scene(r, &s->atmosphere, s->sun_radius_rad, &s->features);
}
