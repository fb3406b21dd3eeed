/* The camera of a render from its EXR matrices (composite_camera.h). */
#include "app/runs/composite_camera.h"
#include <math.h>

/* Inverse of a 3x3 (row-major); false when singular. */
static bool invert3(const double m[3][3], double out[3][3])
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(fabs(det) > 1e-300) || !isfinite(det)) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            out[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return true;
}

/* OpenEXR's worldToCamera (row vectors, p_cam = p_world M; the camera looks along -Z, +X right, +Y up): the
 * camera's position and axes in world coordinates. With worldToNDC (NDC x, y in [-1, 1] across the screen
 * window) also the vertical field of view. */
bool camera_from_matrices(const io_exr_info *info, composite_view *v, double *fov_deg)
{
    const float *M = info->world_to_camera;
    double R[3][3], Ri[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[i][j] = M[4 * i + j];
    if (!invert3(R, Ri)) return false;
    /* c R + t = 0 -> c = -t R^-1; camera axis k in world: row k of R^-1. */
    for (int j = 0; j < 3; ++j) {
        v->camera[j] = -(M[12] * Ri[0][j] + M[13] * Ri[1][j] + M[14] * Ri[2][j]);
        v->right[j] = Ri[0][j], v->up[j] = Ri[1][j], v->forward[j] = -Ri[2][j];
    }
    double *axes[3] = {v->right, v->up, v->forward};
    for (int k = 0; k < 3; ++k) {
        double n = sqrt(axes[k][0] * axes[k][0] + axes[k][1] * axes[k][1] + axes[k][2] * axes[k][2]);
        for (int j = 0; j < 3; ++j) axes[k][j] /= n;
    }
    *fov_deg = 0.0;
    if (info->has_world_to_ndc) {
        /* The camera-space point (0, 1, -1) lands at NDC y = 1 / tan(fov / 2). */
        double p[3], h[4] = {0, 0, 0, 0};
        for (int j = 0; j < 3; ++j) p[j] = v->camera[j] + Ri[1][j] - Ri[2][j];
        const float *N = info->world_to_ndc;
        for (int j = 0; j < 4; ++j) h[j] = p[0] * N[j] + p[1] * N[4 + j] + p[2] * N[8 + j] + N[12 + j];
        double y = h[3] != 0.0 ? fabs(h[1] / h[3]) : 0.0;
        double fov = y > 0.0 ? 2.0 * atan(1.0 / y) * 180.0 / 3.14159265358979323846 : 0.0;
        if (fov >= 1.0 && fov <= 170.0) *fov_deg = fov;
    }
    return true;
}

