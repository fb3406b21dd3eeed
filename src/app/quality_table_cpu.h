/* Measured by tools/tradeoff on llvmpipe (LLVM 15.0.6, 256 bits) (process CPU ms per whole frame at 1280x720, bloom and tone map
 * included, over 6 frames after warm-up; mean relative luminance error at a 96x54 grid of 1280x720 frames vs the
 * converged reference), on a shared 2-core machine (CPU time does not grow with the machine's load as wall time
 * does). Regenerate: tradeoff --size 1280x720 --error-render 1280x720 --frames 6 --cost cpu --emit-table FILE.
 * high, ultra and march32 (lesson) were measured before the sky pass stored its class for the upsample (a few ms
 * of CPU a frame on 850-2900). The row type is quality_table.h's. */
static const quality_measurement quality_table_cpu[] = {
    {"low", 0, 41.5302, 0.02806, 0.03108},
    {"low", 1, 41.0715, 0.02488, 0.03001},
    {"low", 2, 40.0563, 0.01067, 0.01334},
    {"low", 4, 41.1540, 0.01069, 0.02946},
    {"low", 5, 91.8010, 0.00352, 0.02887},
    {"medium", 0, 114.3632, 0.00490, 0.00608},
    {"medium", 1, 116.1168, 0.00475, 0.00706},
    {"medium", 2, 114.9542, 0.00399, 0.00529},
    {"medium", 4, 114.9467, 0.00320, 0.00457},
    {"medium", 5, 498.3738, 0.00020, 0.00169},
    {"high", 0, 1699.0427, 0.00261, 0.00395},
    {"high", 1, 1603.4067, 0.00243, 0.00308},
    {"high", 2, 1658.0435, 0.00400, 0.00525},
    {"high", 4, 1593.8007, 0.00210, 0.00257},
    {"high", 5, 891.9680, 0.00018, 0.00156},
    {"ultra", 0, 2883.1835, 0.00146, 0.00300},
    {"ultra", 1, 2897.5328, 0.00122, 0.00209},
    {"ultra", 2, 2888.8878, 0.00080, 0.00130},
    {"ultra", 4, 2874.4538, 0.00126, 0.00165},
    {"ultra", 5, 1561.5927, 0.00016, 0.00154},
    {"march32", 0, 856.4542, 0.02424, 0.02855},
    {"march32", 1, 860.4680, 0.01978, 0.02633},
    {"march32", 2, 864.3747, 0.01044, 0.01205},
    {"march32", 4, 857.8078, 0.00988, 0.02455},
    {"march32", 5, 494.9305, 0.00211, 0.01615},
    {"skyview96x54", 0, 95.6090, 0.02779, 0.03092},
    {"skyview96x54", 1, 95.4293, 0.02462, 0.02975},
    {"skyview96x54", 2, 98.3535, 0.01040, 0.01301},
    {"skyview96x54", 4, 94.6287, 0.01038, 0.02821},
    {"skyview96x54", 5, 508.3623, 0.00211, 0.01615},
    {"medium-skyview96", 0, 95.7698, 0.00807, 0.01019},
    {"medium-skyview96", 1, 98.5578, 0.00918, 0.01759},
    {"medium-skyview96", 2, 97.4765, 0.00439, 0.00707},
    {"medium-skyview96", 4, 97.2452, 0.00510, 0.00902},
    {"medium-skyview96", 5, 501.0245, 0.00020, 0.00169},
    {"medium-skyview96-scale0.75", 0, 62.3915, 0.00838, 0.01048},
    {"medium-skyview96-scale0.75", 1, 59.9897, 0.00949, 0.01785},
    {"medium-skyview96-scale0.75", 2, 60.2000, 0.00408, 0.00675},
    {"medium-skyview96-scale0.75", 4, 62.2792, 0.00528, 0.00924},
    {"medium-skyview96-scale0.75", 5, 283.6923, 0.00070, 0.00585},
    {"medium-skyview96-scale0.5", 0, 40.5430, 0.00836, 0.01049},
    {"medium-skyview96-scale0.5", 1, 40.7608, 0.00945, 0.01787},
    {"medium-skyview96-scale0.5", 2, 41.2270, 0.00410, 0.00676},
    {"medium-skyview96-scale0.5", 4, 40.7037, 0.00533, 0.00922},
    {"medium-skyview96-scale0.5", 5, 139.7313, 0.00164, 0.01457},
    /* Measured later (same command, --configs medium-skyview96-scale0.5,medium-skyview96-scale0.5-bloomq; CSV
     * docs/perf/lavapipe-post/tradeoff_lavapipe_720_bloomq.csv): the quarter-size bloom. In that run
     * medium-skyview96-scale0.5 cost 41.6-43.9 ms (146 at 400 km), its errors as above. */
    {"medium-skyview96-scale0.5-bloomq", 0, 34.2215, 0.00836, 0.01049},
    {"medium-skyview96-scale0.5-bloomq", 1, 33.8587, 0.00945, 0.01787},
    {"medium-skyview96-scale0.5-bloomq", 2, 33.8513, 0.00410, 0.00676},
    {"medium-skyview96-scale0.5-bloomq", 4, 34.0630, 0.00533, 0.00922},
    {"medium-skyview96-scale0.5-bloomq", 5, 140.7413, 0.00164, 0.01457},
    /* The twilight (-4), sun-0 and twilight (-2) classes with the penumbra sun visibility (issue 17): re-measured
     * 2026-11-25 by tradeoff --cost cpu --scenes twilight,sun0,twilight-2 --frames 10 for the candidates of a CPU
     * device (the march presets, 0.85-2.9 s a frame there, were not re-run: their old twilight rows were the
     * lesson fade's and are dropped). */
    {"low", 3, 46.7469, 0.02036, 0.02712},
    {"medium", 3, 138.3127, 0.00230, 0.00340},
    {"medium-skyview96", 3, 106.4631, 0.00684, 0.00906},
    {"medium-skyview96-scale0.5", 3, 43.2487, 0.00657, 0.00879},
    {"medium-skyview96-scale0.5-bloomq", 3, 37.4650, 0.00657, 0.00879},
    {"skyview96x54", 3, 107.0558, 0.02004, 0.02684},
    {"low", 6, 45.1957, 0.01031, 0.01396},
    {"medium", 6, 134.1309, 0.00169, 0.00302},
    {"medium-skyview96", 6, 104.5082, 0.00340, 0.00632},
    {"medium-skyview96-scale0.5", 6, 45.0183, 0.00312, 0.00609},
    {"medium-skyview96-scale0.5-bloomq", 6, 35.5070, 0.00312, 0.00609},
    {"skyview96x54", 6, 105.3205, 0.01003, 0.01374},
    {"low", 7, 49.8201, 0.01648, 0.02181},
    {"medium", 7, 138.0701, 0.00471, 0.00644},
    {"medium-skyview96", 7, 101.3442, 0.00308, 0.00597},
    {"medium-skyview96-scale0.5", 7, 44.8010, 0.00324, 0.00614},
    {"medium-skyview96-scale0.5-bloomq", 7, 39.6790, 0.00324, 0.00614},
    {"skyview96x54", 7, 106.4572, 0.01619, 0.02150},
};
static const int quality_table_cpu_count = (int)(sizeof quality_table_cpu / sizeof quality_table_cpu[0]);
