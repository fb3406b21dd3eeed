/* Measured by tools/tradeoff --emit-horizon-table on llvmpipe (LLVM 15.0.6, 256 bits): the relative luminance error over the pixels
 * within 2 px of the analytic horizon of a 240x135 frame against the per-pixel march (ultra) of the same
 * view, max and mean (tools/tradeoff_horizon.h). --max-error refuses a configuration whose max on a
 * class exceeds the bound. Regenerate: tradeoff --emit-horizon-table FILE. */
typedef struct quality_horizon { const char *config; int scene; double max, mean; } quality_horizon;
static const quality_horizon quality_horizon_table[] = {
    {"low", 2, 0.21300, 0.01943},
    {"medium", 2, 0.00283, 0.00074},
    {"high", 2, 0.00131, 0.00015},
    {"ultra", 2, 0.00000, 0.00000},
    {"medium-skyview96-s24-scale0.5-bloomq", 2, 0.20648, 0.01990},
    {"low", 4, 0.13881, 0.03880},
    {"medium", 4, 0.00673, 0.00359},
    {"high", 4, 0.00274, 0.00168},
    {"ultra", 4, 0.00000, 0.00000},
    {"medium-skyview96-s24-scale0.5-bloomq", 4, 0.11072, 0.01351},
    /* The 400 km limb (issue 31: tests/test_promise.c found --max-error 0.005 picking low there, whose frame mean
     * grows from 0.37 % at 1280x720 to 2.3 % at 320x180: the limb is a horizon too). Same tool, same size:
     * tradeoff --emit-horizon-table FILE --scenes 400km-limb --horizon-size 240x135 --configs <these five>. */
    {"low", 5, 0.60102, 0.09883},
    {"medium", 5, 0.00764, 0.00278},
    {"high", 5, 0.00262, 0.00118},
    {"ultra", 5, 0.00000, 0.00000},
    {"medium-skyview96-s24-scale0.5-bloomq", 5, 0.60698, 0.09403},
    /* Issue 26 item 5 (widened): the CPU table's other configurations, same tool and size, on the three classes:
     * tradeoff --emit-horizon-table FILE --scenes sunset,10km-horizon,400km-limb --horizon-size 240x135 --configs
     * medium-skyview96,medium-skyview96-scale0.5,medium-skyview96-scale0.5-bloomq,medium-skyview96-scale0.75,
     * skyview96x54,march32 (27 minutes on the shared 2-core machine). */
    {"march32", 2, 0.02036, 0.00804},
    {"skyview96x54", 2, 0.01732, 0.00700},
    {"medium-skyview96", 2, 0.01034, 0.00295},
    {"medium-skyview96-scale0.75", 2, 0.04871, 0.00659},
    {"medium-skyview96-scale0.5", 2, 0.20842, 0.02084},
    {"medium-skyview96-scale0.5-bloomq", 2, 0.20842, 0.02084},
    {"march32", 4, 0.03654, 0.03266},
    {"skyview96x54", 4, 0.04622, 0.03558},
    {"medium-skyview96", 4, 0.01551, 0.00555},
    {"medium-skyview96-scale0.75", 4, 0.09456, 0.01247},
    {"medium-skyview96-scale0.5", 4, 0.11149, 0.01391},
    {"medium-skyview96-scale0.5-bloomq", 4, 0.11149, 0.01391},
    {"march32", 5, 0.02329, 0.01425},
    {"skyview96x54", 5, 0.02329, 0.01425},
    {"medium-skyview96", 5, 0.00764, 0.00278},
    {"medium-skyview96-scale0.75", 5, 0.23825, 0.04210},
    {"medium-skyview96-scale0.5", 5, 0.60698, 0.09403},
    {"medium-skyview96-scale0.5-bloomq", 5, 0.60698, 0.09403},
};
static const int quality_horizon_table_count =
    (int)(sizeof quality_horizon_table / sizeof quality_horizon_table[0]);
