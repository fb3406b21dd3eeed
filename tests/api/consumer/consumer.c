/* The smallest libvksky host: built against an installed vksky (pkg-config or find_package), it checks the ABI and
 * prints the version; with a scene name, the ground radius of that shipped scene as the library finds it. */
#include <vksky.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc == 2) {
        vksky_scene *s = NULL;
        if (vksky_scene_load(argv[1], NULL, NULL, &s) != VKSKY_SUCCESS) return 1;
        printf("%.0f\n", vksky_scene_ground_radius_m(s));
        vksky_scene_destroy(s);
        return 0;
    }
    if (vksky_abi_version() != VKSKY_ABI_VERSION) {
        fprintf(stderr, "consumer: library ABI %u, header ABI %u\n", vksky_abi_version(), VKSKY_ABI_VERSION);
        return 1;
    }
    vksky_context *c = NULL;
    if (vksky_context_create(NULL, &c) != VKSKY_ERROR_INVALID_ARGUMENT) return 1;   /* a call that needs no GPU */
    printf("vksky %s abi %u\n", vksky_version_string(), vksky_abi_version());
    return strlen(vksky_version_string()) > 0 ? 0 : 1;
}
