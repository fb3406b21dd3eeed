/* The aerial-perspective trade, --aerial-perspective auto chooses from it (options_composite.c). Errors measured
 * by tools/tradeoff_aerial --classes on llvmpipe (LLVM 15.0.6, 256 bits): mean relative luminance error of the
 * in-scattering at 32x18 vs the converged reference, the composite's default march (--steps 32, the segments'
 * ramp: --defaults; issue 28 item 7); each method's worst of five view classes (docs/aerial_perspective.md "Honest
 * --max-error": near steep ground is the volumes' worst). GPU ms: ap_volume + composite at 1920x1080 on an NVIDIA
 * H100 (median of 60 frames). Regenerate: tradeoff_aerial --classes --defaults --frames 0 --error-size 32x18
 * --emit-table FILE. */
#ifndef VKSKY_APP_AP_TRADE_TABLE_H
#define VKSKY_APP_AP_TRADE_TABLE_H
typedef struct ap_trade { unsigned size[3]; double range_km, distribution, gpu_ms, err_mean; } ap_trade;
/* size 0x0x0: the per-pixel march. */
static const ap_trade ap_trade_table[] = {
    {{0, 0, 0}, 0.0, 0.0, 2.1687, 0.00290},   /* march */
    {{16, 16, 16}, 32.0, 2.0, 0.1912, 0.05468},   /* volume 16x16x16 */
    {{32, 32, 32}, 32.0, 2.0, 0.1995, 0.02229},   /* volume 32x32x32 */
    {{32, 32, 32}, 32.0, 1.0, 0.1995, 0.12184},   /* volume 32x32x32 linear */
    {{32, 32, 64}, 32.0, 2.0, 0.2281, 0.01441},   /* volume 32x32x64 */
    {{64, 64, 32}, 32.0, 2.0, 0.2967, 0.02226},   /* volume 64x64x32 */
    {{64, 64, 64}, 32.0, 2.0, 0.4312, 0.01437},   /* volume 64x64x64 */
};
enum { AP_TRADE_COUNT = 7 };
#endif
