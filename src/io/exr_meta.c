/* vksky image I/O: EXR header attributes (exr_meta.h). */
#include "io/exr_meta.h"

#include "io/exr_common.h"
#include "io/exr_envmap_attrs.h"
#include "io/io_error.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

exr_result_t io_exr_set_meta(exr_context_t ctxt, int part, const io_exr_meta *m)
{
    exr_result_t rc = EXR_ERR_SUCCESS;
    if (m->chromaticities) {
        const float *c = m->chromaticities;
        exr_attr_chromaticities_t chroma = {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]};
        rc = exr_attr_set_chromaticities(ctxt, part, "chromaticities", &chroma);
    }
    const float *matrices[2] = {m->world_to_camera, m->world_to_ndc};
    const char *matrix_names[2] = {"worldToCamera", "worldToNDC"};
    for (int i = 0; i < 2 && rc == EXR_ERR_SUCCESS; ++i) {
        if (!matrices[i]) continue;
        exr_attr_m44f_t mat;
        memcpy(mat.m, matrices[i], sizeof mat.m);
        rc = exr_attr_set_m44f(ctxt, part, matrix_names[i], &mat);
    }
    for (int i = 0; i < m->string_count && rc == EXR_ERR_SUCCESS; ++i)
        rc = exr_attr_set_string(ctxt, part, m->strings[i].name, m->strings[i].value);
    for (int i = 0; i < 4 && m->float_names[i] && rc == EXR_ERR_SUCCESS; ++i)
        rc = exr_attr_set_float(ctxt, part, m->float_names[i], m->float_values[i]);
    if (m->int_name && rc == EXR_ERR_SUCCESS) rc = exr_attr_set_int(ctxt, part, m->int_name, m->int_value);
    if (m->sky && rc == EXR_ERR_SUCCESS) rc = io_exr_add_sky_attrs(ctxt, part, m->sky);
    return rc;
}

/* The header of `path` opened for reading (0), or -1 + err. */
static int open_header(const char *path, exr_context_t *ctxt, char *err, size_t err_size)
{
    *ctxt = NULL;
    if (io_check_readable(path, err, err_size) != 0) return -1;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = io_exr_error_handler;
    io_exr_clear_msg();
    exr_result_t rc = exr_start_read(ctxt, path, &init);
    if (rc != EXR_ERR_SUCCESS) {
        io_set_err(err, err_size, "cannot read '%s': not an OpenEXR file (%s)", io_safe_path(path), io_exr_msg(rc));
        if (*ctxt) exr_finish(ctxt);
        return -1;
    }
    return 0;
}

int io_exr_read_int_attr(const char *path, const char *name, int *out, char *err, size_t err_size)
{
    exr_context_t ctxt;
    if (!out || !name) {
        io_set_err(err, err_size, "cannot read '%s': NULL argument", io_safe_path(path));
        return -1;
    }
    if (open_header(path, &ctxt, err, err_size) != 0) return -1;
    const exr_attribute_t *attr = NULL;
    int found = 1;
    if (exr_get_attribute_by_name(ctxt, 0, name, &attr) == EXR_ERR_SUCCESS && attr && attr->type == EXR_ATTR_INT)
        *out = attr->i, found = 0;
    exr_finish(&ctxt);
    return found;
}

int io_exr_read_string_attr(const char *path, const char *name, char **out, char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (out) *out = NULL;
    if (!out || !name) {
        io_set_err(err, err_size, "cannot read '%s': NULL argument", p);
        return -1;
    }
    exr_context_t ctxt;
    if (open_header(path, &ctxt, err, err_size) != 0) return -1;
    const exr_attribute_t *attr = NULL;
    int found = 1;
    if (exr_get_attribute_by_name(ctxt, 0, name, &attr) == EXR_ERR_SUCCESS && attr && attr->type == EXR_ATTR_STRING &&
        attr->string) {
        int32_t length = attr->string->length;
        *out = malloc((size_t)length + 1);
        if (!*out) {
            io_set_err(err, err_size, "cannot read '%s': out of memory", p);
            found = -1;
        } else {
            memcpy(*out, attr->string->str, (size_t)length);
            (*out)[length] = '\0';
            found = 0;
        }
    }
    exr_finish(&ctxt);
    return found;
}
