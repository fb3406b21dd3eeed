/* make_corpus DIR: writes the EXR fuzz seed corpus (small files, one per shape the reader handles) with OpenEXRCore's
 * own encoder (tests/exr_core_writer.h). Run once by hand; its output is committed in tests/fuzz/corpus/ (a DWAA
 * seed made by oiiotool is added there too, since the C library cannot write DWA). */
#include "../exr_core_writer.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_corpus DIR\n");
        return 2;
    }
    static const char *codec[] = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a"};
    int fails = 0;
    char path[512];
    for (int comp = 0; comp < 8; ++comp) {
        for (int tiled = 0; tiled < 2; ++tiled) {
            if (tiled && comp != 0 && comp != 3 && comp != 4 && comp != 7) continue; /* a few tiled ones */
            tw_part P = {.name = "rgba", .tiled = tiled, .tile_w = 4, .tile_h = 4, .compression = comp, .x0 = -1,
                         .y0 = 2, .w = 8, .h = tiled ? 8 : 6, .nch = 4, .smooth = comp >= 5,
                         .ch = {{"A", EXR_PIXEL_HALF}, {"B", EXR_PIXEL_HALF}, {"G", EXR_PIXEL_FLOAT},
                                {"R", EXR_PIXEL_UINT}}};
            snprintf(path, sizeof path, "%s/%s_%s.exr", argv[1], tiled ? "tiled" : "scan", codec[comp]);
            fails += tw_write(path, &P, 1) != 0;
        }
    }
    tw_part mp[2] = {
        {.name = "ViewLayer.Combined", .compression = EXR_COMPRESSION_ZIP, .w = 8, .h = 4, .nch = 3, .has_w2c = 1,
         .has_w2n = 1,
         .ch = {{"ViewLayer.Combined.B", EXR_PIXEL_HALF}, {"ViewLayer.Combined.G", EXR_PIXEL_HALF},
                {"ViewLayer.Combined.R", EXR_PIXEL_HALF}}},
        {.name = "ViewLayer.Position", .tiled = 1, .tile_w = 8, .tile_h = 2, .compression = EXR_COMPRESSION_RLE,
         .w = 8, .h = 4, .nch = 3,
         .ch = {{"ViewLayer.Position.X", EXR_PIXEL_FLOAT}, {"ViewLayer.Position.Y", EXR_PIXEL_FLOAT},
                {"ViewLayer.Position.Z", EXR_PIXEL_FLOAT}}}};
    for (int i = 0; i < 16; ++i) mp[0].w2c[i] = mp[0].w2n[i] = (float)i;
    snprintf(path, sizeof path, "%s/multipart_blender.exr", argv[1]);
    fails += tw_write(path, mp, 2) != 0;
    mp[1].h = 3; /* parts of different sizes */
    snprintf(path, sizeof path, "%s/multipart_mismatch.exr", argv[1]);
    fails += tw_write(path, mp, 2) != 0;
    tw_part edge = {.name = "e", .tiled = 1, .tile_w = 4, .tile_h = 4, .compression = EXR_COMPRESSION_B44, .w = 5,
                    .h = 5, .nch = 2, .smooth = 1, .ch = {{"R", EXR_PIXEL_HALF}, {"Z", EXR_PIXEL_FLOAT}}};
    snprintf(path, sizeof path, "%s/tiled_b44_edge.exr", argv[1]);
    fails += tw_write(path, &edge, 1) != 0;
    tw_part sub = {.name = "s", .compression = EXR_COMPRESSION_RLE, .w = 8, .h = 4, .nch = 2, .sampling = 2,
                   .ch = {{"Y", EXR_PIXEL_HALF}, {"RY", EXR_PIXEL_HALF}}};
    snprintf(path, sizeof path, "%s/scan_subsampled.exr", argv[1]);
    fails += tw_write(path, &sub, 1) != 0;
    return fails ? 1 : 0;
}
