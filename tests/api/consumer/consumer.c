/* The smallest libvksky host: built against an installed vksky (pkg-config or find_package), it checks the ABI and
 * prints the version. */
#include <vksky.h>
#include <stdio.h>
#include <string.h>

int main(void)
{
    if (vksky_abi_version() != VKSKY_ABI_VERSION) {
        fprintf(stderr, "consumer: library ABI %u, header ABI %u\n", vksky_abi_version(), VKSKY_ABI_VERSION);
        return 1;
    }
    vksky_context *c = NULL;
    if (vksky_context_create(NULL, &c) != VKSKY_ERROR_INVALID_ARGUMENT) return 1;   /* a call that needs no GPU */
    printf("vksky %s abi %u\n", vksky_version_string(), vksky_abi_version());
    return strlen(vksky_version_string()) > 0 ? 0 : 1;
}
