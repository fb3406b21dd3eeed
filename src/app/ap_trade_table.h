/* The aerial-perspective trade, --aerial-perspective auto chooses from it (options_composite.c). Measured
 * by tools/tradeoff_aerial on NVIDIA H100 80GB HBM3 (ap_volume + composite GPU ms at 1920x1080, median of 60
 * frames; mean relative luminance error of the in-scattering at 64x36 vs the converged
 * reference, 128 march steps). Regenerate: tradeoff_aerial --emit-table FILE. */
#ifndef VKSKY_APP_AP_TRADE_TABLE_H
#define VKSKY_APP_AP_TRADE_TABLE_H
typedef struct ap_trade { unsigned size[3]; double range_km, distribution, gpu_ms, err_mean; } ap_trade;
/* size 0x0x0: the per-pixel march. */
static const ap_trade ap_trade_table[] = {
    {{0, 0, 0}, 0.0, 0.0, 2.1687, 0.00191},   /* march */
    {{16, 16, 16}, 32.0, 2.0, 0.1912, 0.00913},   /* volume 16x16x16 */
    {{32, 32, 32}, 32.0, 2.0, 0.1995, 0.00527},   /* volume 32x32x32 */
    {{32, 32, 32}, 32.0, 1.0, 0.1995, 0.01100},   /* volume 32x32x32 linear */
    {{32, 32, 64}, 32.0, 2.0, 0.2281, 0.00372},   /* volume 32x32x64 */
    {{64, 64, 32}, 32.0, 2.0, 0.2967, 0.00518},   /* volume 64x64x32 */
    {{64, 64, 64}, 32.0, 2.0, 0.4312, 0.00356},   /* volume 64x64x64 */
};
enum { AP_TRADE_COUNT = 7 };
#endif
