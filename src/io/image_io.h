/* vksky image I/O, all of it: kept only for src/app/window.c until its split (issue 11) includes the pieces it uses.
 * New code includes the piece it needs: exr_write.h, exr_read.h, png_io.h, atomic_file.h, half_float.h. */
#ifndef VKSKY_IO_IMAGE_IO_H
#define VKSKY_IO_IMAGE_IO_H

#include "io/atomic_file.h"
#include "io/exr_read.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include "io/png_io.h"

#endif /* VKSKY_IO_IMAGE_IO_H */
