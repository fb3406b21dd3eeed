/* Pixel <-> direction (see sky/projection.h); the same formulas as shaders/glsl/projection.glsl. */
#include "sky/projection.h"
#include <math.h>

static const double PI = 3.14159265358979323846;

void projection_image_size(sky_projection p, int width, int height, int *out_width, int *out_height)
{
    *out_width = width;
    *out_height = p == SKY_PROJECTION_EQUIRECT ? (width / 2 > 0 ? width / 2 : 1)
                  : p == SKY_PROJECTION_CUBEMAP ? 6 * width
                  : p == SKY_PROJECTION_FISHEYE ? width
                  : height;
}

void projection_dir_from_angles(double azimuth_deg, double elevation_deg, double dir[3])
{
    double az = azimuth_deg * PI / 180.0, el = elevation_deg * PI / 180.0;
    dir[0] = cos(el) * cos(az), dir[1] = sin(el), dir[2] = cos(el) * sin(az);
}

/* OpenEXR's face directions: a left to right, b top to bottom, both in [-1, 1]. */
static void cube_dir(int face, double a, double b, double d[3])
{
    static const double table[6][3][3] = {
        /* rows: x, y, z as (coefficient of a, of b, constant) */
        {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}},     /* +X: ( 1, -b,  a) */
        {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}},   /* -X: (-1, -b, -a) */
        {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},     /* +Y: ( a,  1, -b) */
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},     /* -Y: ( a, -1,  b) */
        {{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}},    /* +Z: (-a, -b,  1) */
        {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}},    /* -Z: ( a, -b, -1) */
    };
    for (int i = 0; i < 3; ++i) d[i] = table[face][i][0] * a + table[face][i][1] * b + table[face][i][2];
}

bool projection_dir(sky_projection p, int width, int height, double x, double y, double dir[3])
{
    double u = x / width, v = y / height;
    if (p == SKY_PROJECTION_EQUIRECT) {
        double lon = PI * (1.0 - 2.0 * u), lat = PI * (0.5 - v);
        dir[0] = sin(lon) * cos(lat), dir[1] = sin(lat), dir[2] = cos(lon) * cos(lat);
        return true;
    }
    if (p == SKY_PROJECTION_CUBEMAP) {
        double fy = y / width;
        int face = (int)floor(fy);
        if (face < 0) face = 0;
        if (face > 5) face = 5;
        double d[3];
        cube_dir(face, 2.0 * u - 1.0, 2.0 * (fy - face) - 1.0, d);
        double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int i = 0; i < 3; ++i) dir[i] = d[i] / n;
        return true;
    }
    if (p == SKY_PROJECTION_FISHEYE) {
        double qx = 2.0 * u - 1.0, qy = 1.0 - 2.0 * v, r = sqrt(qx * qx + qy * qy);
        double theta = fmin(r, 1.0) * 0.5 * PI;
        double hx = r > 0 ? qx / r : 0.0, hy = r > 0 ? qy / r : 1.0;
        dir[0] = sin(theta) * hy, dir[1] = cos(theta), dir[2] = -sin(theta) * hx;
        return r <= 1.0;
    }
    return false;
}

bool projection_pixel(sky_projection p, int width, int height, const double dir[3], double *x, double *y)
{
    double n = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(n > 0)) return false;
    double d[3] = {dir[0] / n, dir[1] / n, dir[2] / n};
    if (p == SKY_PROJECTION_EQUIRECT) {
        double lon = atan2(d[0], d[2]), lat = asin(fmax(-1.0, fmin(1.0, d[1])));
        *x = (1.0 - lon / PI) * 0.5 * width;
        *y = (0.5 - lat / PI) * height;
        return true;
    }
    if (p == SKY_PROJECTION_CUBEMAP) {
        int axis = fabs(d[0]) >= fabs(d[1]) && fabs(d[0]) >= fabs(d[2]) ? 0 : fabs(d[1]) >= fabs(d[2]) ? 1 : 2;
        int face = 2 * axis + (d[axis] < 0);
        double m = fabs(d[axis]), a, b;
        double s[3] = {d[0] / m, d[1] / m, d[2] / m};
        switch (face) {   /* the inverse of cube_dir */
        case 0: a = s[2], b = -s[1]; break;
        case 1: a = -s[2], b = -s[1]; break;
        case 2: a = s[0], b = -s[2]; break;
        case 3: a = s[0], b = s[2]; break;
        case 4: a = -s[0], b = -s[1]; break;
        default: a = s[0], b = -s[1]; break;
        }
        *x = 0.5 * (a + 1.0) * width;
        *y = (face + 0.5 * (b + 1.0)) * width;
        return true;
    }
    if (p == SKY_PROJECTION_FISHEYE) {
        if (d[1] < 0) return false;
        double theta = acos(fmin(1.0, d[1])), h = sqrt(d[0] * d[0] + d[2] * d[2]);
        double r = theta / (0.5 * PI);
        double hx = h > 0 ? -d[2] / h : 0.0, hy = h > 0 ? d[0] / h : 1.0;
        *x = 0.5 * (1.0 + r * hx) * width;
        *y = 0.5 * (1.0 - r * hy) * height;
        return true;
    }
    return false;
}
