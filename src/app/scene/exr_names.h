/* The names of vksky's own EXR header attributes (app/runs/exr_header.h writes them; the scene loader reads the scene
 * back). Header-only, so that the loader needs nothing else of the header's writer. */
#ifndef VKSKY_APP_EXR_NAMES_H
#define VKSKY_APP_EXR_NAMES_H
#define EXR_HEADER_SCENE "vksky:scene"
#define EXR_HEADER_COMMAND_LINE "vksky:commandLine"
#define EXR_HEADER_FRAME "vksky:frame"
#define EXR_HEADER_UNITS "vksky:units"   /* io/exr_sky_attrs.h writes it; --scene OUT.exr reads it back */
#endif
