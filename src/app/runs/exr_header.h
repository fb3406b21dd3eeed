/* What vksky writes into an EXR's header so that the file says how it was made (issue 14 item 5): chromaticities
 * (linear Rec.709 primaries, D65 white), worldToCamera and worldToNDC of the perspective camera, owner and software
 * with the version, the effective scene as JSON ("vksky:scene", the --dump-scene text; `vksky --scene FILE.exr` reads
 * it back), the command line ("vksky:commandLine"), the frame number of a sequence ("vksky:frame"), and for a sun
 * from a date and place the standard capDate, utcOffset, latitude, longitude and altitude.
 *
 * World space: vksky's, +Y up, origin on the ground below the camera, kilometres; the camera at (0, altitude, 0).
 * Camera space is OpenEXR's (RenderMan's): x right, y up, z along the view (left-handed); NDC (0,0) is the image's
 * top-left corner, (1,1) its bottom-right; p_ndc = (p_world, 1) worldToNDC, divided by its w. */
#ifndef VKSKY_APP_EXR_HEADER_H
#define VKSKY_APP_EXR_HEADER_H
#include "app/cli/options_struct.h"
#include "io/exr_meta.h"
#include "io/exr_sky_attrs.h"

#include "app/scene/exr_names.h"

typedef struct exr_header {
    io_exr_meta meta;
    float chromaticities[8], world_to_camera[16], world_to_ndc[16];
    io_exr_string_attr strings[5];
    char *scene_json, *command_line;    /* malloc'd */
    char software[64], cap_date[40];
    io_exr_sky_attrs sky;               /* the sun and the units (app/scene/light.h) */
} exr_header;

/* The header of frame `frame` (-1: not a sequence) rendered from *o. 0 ok, 1 out of memory. exr_header_free after. */
int exr_header_build(exr_header *h, const options *o, int frame);
void exr_header_free(exr_header *h);
/* The command line as one shell-quoted string, the program as "vksky", without --frame-range and --skip-existing
 * (which only say which job of a sequence rendered a frame and whether it resumed: the frames of any split, resumed
 * or not, are the same files). malloc'd; NULL: out of memory. */
char *exr_header_command_line(int argc, char **argv);
#endif
