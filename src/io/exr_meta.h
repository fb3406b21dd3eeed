/* vksky image I/O: header attributes of the EXRs vksky writes (how a file was made, for compositing tools and to
 * reproduce it), and reading a string attribute back. Errors follow io_error.h. */
#ifndef VKSKY_IO_EXR_META_H
#define VKSKY_IO_EXR_META_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct io_exr_string_attr {
    const char *name, *value;
} io_exr_string_attr;

/* Every pointer may be NULL (the attribute is left out). Matrices in OpenEXR's (Imath's) layout: row vectors,
   p' = p M, m[4 * row + column], translation in m[12..14]. */
typedef struct io_exr_meta {
    const float *chromaticities;          /* 8: red x y, green x y, blue x y, white x y ("chromaticities") */
    const float *world_to_camera;         /* 16 ("worldToCamera") */
    const float *world_to_ndc;            /* 16 ("worldToNDC") */
    const io_exr_string_attr *strings;    /* "owner", "software", ... */
    int string_count;
    const char *float_names[4];           /* float attributes ("latitude", ...): names, NULL-terminated */
    float float_values[4];
    const char *int_name;                 /* one int attribute (NULL: none) */
    int int_value;
    const struct io_exr_sky_attrs *sky;   /* the sky's attributes (exr_sky_attrs.h; NULL: none) */
} io_exr_meta;

/* The string attribute `name` of the first part of the EXR at `path` into a malloc'd NUL-terminated copy (*out; free()
   it). Returns 0 when found, 1 when the file has no such string attribute (*out NULL), -1 when the file cannot be read
   as an EXR (err gets the reason, e.g. "cannot read 'x.exr': not an OpenEXR file"). */
int io_exr_read_string_attr(const char *path, const char *name, char **out, char *err, size_t err_size);
/* The int attribute `name` of the first part (e.g. "vksky:frame") into *out: 0 found, 1 none of that name and type,
   -1 not readable as an EXR (err). */
int io_exr_read_int_attr(const char *path, const char *name, int *out, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_EXR_META_H */
