/* The colour axis of the trade (issue 32 item 5): the worst CIEDE2000 per scene class (quality_scenes' order: noon,
 * afternoon, sunset, twilight, 10 km, 400 km, sun 0, twilight -2) of each colour setting (0: RGB; N: --spectral N)
 * against the spectral reference at 48 wavelengths, both the converged model: tools/color_error [--test-wavelengths
 * N] on the 57 rows of docs/model_error.md, the rows binned by quality_scene_class (docs/spectral.md, "The colour
 * axis"). The wavelength count's colour error alone; the GPU's numerics at a preset add their own (CIEDE2000 p95
 * <= 0.43 at --quality high, the same for RGB and spectral: docs/spectral.md). Every preset renders RGB, so a
 * preset's colour error is the RGB row's. Measured on the development VM (CPU, no GPU involved). */
typedef struct quality_color { int wavelengths; double worst_de[QUALITY_SCENE_COUNT]; } quality_color;
static const quality_color quality_color_table[] = {
    {0, {2.40, 2.37, 11.89, 29.30, 28.56, 34.05, 17.12, 20.11}},
    {4, {5.36, 5.80, 9.20, 24.20, 19.22, 21.49, 13.93, 16.65}},
    {8, {0.75, 1.30, 2.56, 6.79, 7.59, 7.04, 2.24, 4.49}},
    {16, {0.13, 0.20, 0.59, 1.48, 1.50, 1.08, 0.83, 1.22}},
    {24, {0.02, 0.03, 0.06, 0.34, 0.43, 0.41, 0.11, 0.22}},
    {32, {0.02, 0.03, 0.09, 0.23, 0.21, 0.15, 0.12, 0.18}},
};
static const int quality_color_table_count = (int)(sizeof quality_color_table / sizeof quality_color_table[0]);
