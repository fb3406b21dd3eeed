/* The composite's camera from a render's EXR attributes (issue 12): OpenEXR's worldToCamera and worldToNDC as the
 * camera's position, axes and vertical field of view in the render's world (include/vksky.h's vksky_composite_view).
 * A host of include/vksky.h: no src/sky or src/lib header. */
#ifndef VKSKY_APP_COMPOSITE_CAMERA_H
#define VKSKY_APP_COMPOSITE_CAMERA_H
#include "app/runs/composite_layers.h"
#include "io/exr_read.h"
#include <stdbool.h>

/* The camera's position and axes into *v (its other fields left), and *fov_deg: the vertical field of view from
 * worldToNDC (0 when the file has none or it is outside 1..170 degrees). false: worldToCamera is singular. */
bool camera_from_matrices(const io_exr_info *info, composite_view *v, double *fov_deg);
#endif
