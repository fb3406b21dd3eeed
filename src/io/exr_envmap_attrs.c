/* vksky image I/O: the sky's header attributes (see exr_envmap_attrs.h). */
#include "io/exr_envmap_attrs.h"
#include "io/exr_common.h"

exr_result_t io_exr_add_sky_attrs(exr_context_t ctxt, int part, const io_exr_sky_attrs *a)
{
    exr_result_t rc = EXR_ERR_SUCCESS;
    if (!a) return rc;
    /* The standard attribute: OpenImageIO, Nuke and the OpenEXR tools recognise an environment map by it. */
    if (a->envmap != IO_ENVMAP_NONE)
        rc = exr_attr_set_envmap(ctxt, part, "envmap", a->envmap == IO_ENVMAP_CUBE ? EXR_ENVMAP_CUBE : EXR_ENVMAP_LATLONG);
    if (rc == EXR_ERR_SUCCESS && a->projection) rc = exr_attr_set_string(ctxt, part, "vksky:projection", a->projection);
    if (rc == EXR_ERR_SUCCESS && a->units) rc = exr_attr_set_string(ctxt, part, "vksky:units", a->units);
    if (rc == EXR_ERR_SUCCESS && a->white_luminance > 0.0f)
        rc = exr_attr_set_float(ctxt, part, "whiteLuminance", a->white_luminance);
    if (rc == EXR_ERR_SUCCESS && a->has_sun) {
        /* The sun as a separate light (a --no-sun-disc map plus a distant light is the usual workflow). */
        exr_attr_v3f_t d = {.x = a->sun_direction[0], .y = a->sun_direction[1], .z = a->sun_direction[2]};
        exr_attr_v3f_t e = {.x = a->sun_illuminance[0], .y = a->sun_illuminance[1], .z = a->sun_illuminance[2]};
        rc = exr_attr_set_v3f(ctxt, part, "vksky:sunDirection", &d);
        exr_attr_v3f_t c = {.x = a->sun_at_camera[0], .y = a->sun_at_camera[1], .z = a->sun_at_camera[2]};
        if (rc == EXR_ERR_SUCCESS) rc = exr_attr_set_v3f(ctxt, part, "vksky:sunIlluminance", &e);
        if (rc == EXR_ERR_SUCCESS) rc = exr_attr_set_v3f(ctxt, part, "vksky:sunIlluminanceAtCamera", &c);
        if (rc == EXR_ERR_SUCCESS && a->sun_units)
            rc = exr_attr_set_string(ctxt, part, "vksky:sunIlluminanceUnits", a->sun_units);
    }
    /* How the file was made (chromaticities, software, vksky:scene, the command line): every EXR says it. */
    if (rc == EXR_ERR_SUCCESS && a->meta) rc = io_exr_set_meta(ctxt, part, a->meta);
    return rc;
}
