/* Shipped scene lookup (scene_find.h). The directories, in order: in libvksky, VKSKY_SCENE_DIR_FROM_LIB relative to
 * the directory of the shared library itself (an installed library serves a host program anywhere); then
 * VKSKY_SCENE_DIR_FROM_BIN relative to the directory of /proc/self/exe (the install tree), then
 * VKSKY_SOURCE_SCENE_DIR (the source tree at build time). */
#ifdef VKSKY_SCENE_DIR_FROM_LIB
#define _GNU_SOURCE   /* dladdr: where the library itself was loaded from */
#include <dlfcn.h>
#endif
#include "app/scene/scene_find.h"
#include "app/cli/bad_value.h"
#include <cjson/cJSON.h>
#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef VKSKY_SCENE_DIR_FROM_BIN
#define VKSKY_SCENE_DIR_FROM_BIN "../share/vksky/scenes"
#endif
#ifndef VKSKY_SOURCE_SCENE_DIR
#define VKSKY_SOURCE_SCENE_DIR "scenes"
#endif
#define MAX_DIRS 3
#define MAX_SCENES 64
#define DESCRIPTION_COLUMNS 76   /* name column + this fit in 100 columns */

static bool is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The scene directories that exist, install tree first. */
static int scene_dirs(char dirs[MAX_DIRS][PATH_MAX])
{
    int n = 0;
#ifdef VKSKY_SCENE_DIR_FROM_LIB
    /* The file this function was loaded from: libvksky.so (a static library's host gets its own program). */
    Dl_info info;
    if (dladdr((void *)scene_dirs, &info) && info.dli_fname && strrchr(info.dli_fname, '/')) {
        const char *slash = strrchr(info.dli_fname, '/');
        if (snprintf(dirs[n], PATH_MAX, "%.*s/%s", (int)(slash - info.dli_fname), info.dli_fname,
                     VKSKY_SCENE_DIR_FROM_LIB) < PATH_MAX && is_dir(dirs[n]))
            ++n;
    }
#endif
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            if (snprintf(dirs[n], PATH_MAX, "%s/%s", exe, VKSKY_SCENE_DIR_FROM_BIN) < PATH_MAX && is_dir(dirs[n])) ++n;
        }
    }
    if (snprintf(dirs[n], PATH_MAX, "%s", VKSKY_SOURCE_SCENE_DIR) < PATH_MAX && is_dir(dirs[n])) ++n;
    return n;
}

bool scene_is_name(const char *value)
{
    size_t n = strlen(value);
    struct stat st;
    return n > 0 && !strchr(value, '/') && !(n >= 5 && !strcmp(value + n - 5, ".json")) &&
           !(n >= 4 && !strcasecmp(value + n - 4, ".exr")) && stat(value, &st) != 0;
}

static int compare_names(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* The shipped names (sorted, deduplicated: the install tree shadows the source tree) and the directory of each. */
static int scene_names(char dirs[MAX_DIRS][PATH_MAX], int dir_count, char *names[MAX_SCENES], int where[MAX_SCENES])
{
    int count = 0;
    for (int d = 0; d < dir_count; ++d) {
        DIR *dir = opendir(dirs[d]);
        if (!dir) continue;
        for (struct dirent *e; (e = readdir(dir)) && count < MAX_SCENES;) {
            size_t n = strlen(e->d_name);
            if (n <= 5 || strcmp(e->d_name + n - 5, ".json") || e->d_name[0] == '.') continue;
            char *name = strndup(e->d_name, n - 5);
            bool seen = false;
            for (int i = 0; i < count && name; ++i) seen |= !strcmp(names[i], name);
            if (!name || seen) { free(name); continue; }
            names[count] = name, where[count++] = d;
        }
        closedir(dir);
    }
    /* Sort names and their directories together: sort pointers, then look the directories up again. */
    char *sorted[MAX_SCENES];
    int sorted_where[MAX_SCENES];
    memcpy(sorted, names, sizeof(char *) * (size_t)count);
    qsort(sorted, (size_t)count, sizeof sorted[0], compare_names);
    for (int i = 0; i < count; ++i)
        for (int k = 0; k < count; ++k)
            if (sorted[i] == names[k]) sorted_where[i] = where[k];
    memcpy(names, sorted, sizeof(char *) * (size_t)count);
    memcpy(where, sorted_where, sizeof(int) * (size_t)count);
    return count;
}

bool scene_find(const char *name, char *out, size_t n)
{
    char dirs[MAX_DIRS][PATH_MAX];
    int dir_count = scene_dirs(dirs);
    for (int d = 0; d < dir_count; ++d) {
        struct stat st;
        if (snprintf(out, n, "%s/%s.json", dirs[d], name) < (int)n && stat(out, &st) == 0 && S_ISREG(st.st_mode))
            return true;
    }
    char *names[MAX_SCENES];
    int where[MAX_SCENES], count = scene_names(dirs, dir_count, names, where);
    char list[400] = "";
    size_t used = 0;
    for (int i = 0; i < count; ++i) {
        int w = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
        if (w > 0 && (size_t)w < sizeof list - used) used += (size_t)w;
        free(names[i]);
    }
    char shown[64];
    size_t k = 0;
    for (; name[k] && k + 1 < sizeof shown; ++k) shown[k] = (unsigned char)name[k] < 0x20 ? '?' : name[k];
    shown[k] = '\0';
    if (count)
        fprintf(options_report_stream(), "vksky: --scene: no file and no shipped scene named '%s'; expected FILE.json or one of: %s "
                        "(vksky --list-scenes)\n", shown, list);
    else
        fprintf(options_report_stream(), "vksky: --scene: no file '%s' and no shipped scenes found (looked in %s relative to the binary "
                        "and %s); expected FILE.json\n", shown, VKSKY_SCENE_DIR_FROM_BIN, VKSKY_SOURCE_SCENE_DIR);
    return false;
}

/* The description's first sentence (up to ". " or the end), cut to `columns` with "...". */
static void first_sentence(const char *text, char *out, size_t columns)
{
    size_t n = 0;
    for (; text[n] && !(text[n] == '.' && (text[n + 1] == ' ' || !text[n + 1])); ++n) {}
    if (n > columns) {
        n = columns - 3;
        while (n > 0 && text[n] != ' ') --n;   /* cut at a word */
        memcpy(out, text, n);
        strcpy(out + n, "...");
    } else {
        memcpy(out, text, n);
        out[n] = '\0';
    }
    for (char *c = out; *c; ++c)
        if ((unsigned char)*c < 0x20) *c = ' ';
}

static void describe(const char *path, char *out, size_t columns)
{
    strcpy(out, "(no description)");
    FILE *f = fopen(path, "rb");
    if (!f) return;
    char *text = malloc(1 << 20);
    size_t len = text ? fread(text, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    if (!text) return;
    text[len] = '\0';
    cJSON *root = cJSON_Parse(text);
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(root, "description");
    if (cJSON_IsString(d)) first_sentence(d->valuestring, out, columns);
    else if (!root) strcpy(out, "(not valid JSON)");
    cJSON_Delete(root);
    free(text);
}

int scene_list(FILE *out)
{
    char dirs[MAX_DIRS][PATH_MAX];
    int dir_count = scene_dirs(dirs);
    char *names[MAX_SCENES];
    int where[MAX_SCENES], count = scene_names(dirs, dir_count, names, where);
    int width = 0;
    for (int i = 0; i < count; ++i) width = (int)strlen(names[i]) > width ? (int)strlen(names[i]) : width;
    if (width > 22) width = 22;
    for (int i = 0; i < count; ++i) {
        char path[PATH_MAX + 80], line[DESCRIPTION_COLUMNS + 1];
        snprintf(path, sizeof path, "%s/%s.json", dirs[where[i]], names[i]);
        describe(path, line, (size_t)(100 - 2 - width - 2) < DESCRIPTION_COLUMNS ? (size_t)(100 - 4 - width) : DESCRIPTION_COLUMNS);
        fprintf(out, "  %-*s  %s\n", width, names[i], line);
        free(names[i]);
    }
    if (!count) fprintf(options_report_stream(), "vksky: --list-scenes: no shipped scenes found\n");
    return count ? 0 : 1;
}
