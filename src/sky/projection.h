/* Pixel <-> direction for every projection, in double: the C twin of shaders/glsl/projection.glsl (the shaders'
 * maths, written once more for tests and for placing the sun in the file's header). World axes: +Y up, azimuth 0 =
 * +X, 90 = +Z (docs/model.md "Directions"); conventions in docs/readme/envmap.md. Pixel coordinates are continuous:
 * pixel (i, j) covers [i, i+1) x [j, j+1), its centre is (i + 0.5, j + 0.5). */
#ifndef VKSKY_SKY_PROJECTION_H
#define VKSKY_SKY_PROJECTION_H
#include <stdbool.h>

typedef enum sky_projection {
    SKY_PROJECTION_PERSPECTIVE = 0,    /* = VKSKY_PROJECTION_* (shared.h) */
    SKY_PROJECTION_EQUIRECT = 1,
    SKY_PROJECTION_CUBEMAP = 2,
    SKY_PROJECTION_FISHEYE = 3,
} sky_projection;

/* The image size a projection makes of --width (equirect: W x W/2, cube map: face W, W x 6W, fisheye: W x W);
 * perspective keeps the height given. */
void projection_image_size(sky_projection p, int width, int height, int *out_width, int *out_height);

/* The direction of continuous pixel position (x, y) in a width x height image; false where the projection has none
 * (outside the fisheye's circle). Perspective: not handled here (its ray matrix lives in sky/view_params.c). */
bool projection_dir(sky_projection p, int width, int height, double x, double y, double dir[3]);

/* The continuous pixel position of a direction (unit or not); false for perspective. Cube map: the face is the
 * direction's largest component, as OpenEXR's CubeMap::faceAndPixelPosition picks it. Fisheye: false below the
 * horizon. */
bool projection_pixel(sky_projection p, int width, int height, const double dir[3], double *x, double *y);

/* dir(az, el) = (cos el cos az, sin el, cos el sin az), degrees. */
void projection_dir_from_angles(double azimuth_deg, double elevation_deg, double dir[3]);
#endif
