/* The pipeline cache on disk (see gpu/pipeline_cache.h). */
#include "gpu/pipeline_cache.h"
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Our header before the driver's data: all fields little-endian as written by this machine (a file from another
 * machine fails the device check anyway). */
enum { HEADER_SIZE = 64, KEY_SIZE = 32, MAX_FILE = 256 << 20 };
static const char MAGIC[8] = {'V', 'K', 'S', 'K', 'Y', 'P', 'C', '1'};

struct gpu_cache_file {
    char path[4096];
    char dir[4096];          /* where the path is: also the home of gpu_cache_blob_* files */
    size_t loaded_size;      /* of the driver data seeded from the file (0: none) */
    uint64_t loaded_sum;
    char key[KEY_SIZE];
};

static uint64_t fnv1a64(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

static uint32_t read_u32(const unsigned char *p) { uint32_t v; memcpy(&v, p, 4); return v; }
static uint64_t read_u64(const unsigned char *p) { uint64_t v; memcpy(&v, p, 8); return v; }

const char *gpu_pipeline_cache_check(const unsigned char *file, size_t size, const char *build_key,
                                     const VkPhysicalDeviceProperties *props)
{
    if (size < sizeof MAGIC || memcmp(file, MAGIC, sizeof MAGIC)) return "not a vksky pipeline cache";
    if (size < HEADER_SIZE) return "truncated";
    uint64_t data_size = read_u64(file + 48);
    if (data_size != size - HEADER_SIZE) return "truncated";
    if (fnv1a64(file + HEADER_SIZE, size - HEADER_SIZE) != read_u64(file + 56)) return "corrupt (checksum)";
    char key[KEY_SIZE] = {0};
    strncpy(key, build_key, KEY_SIZE - 1);
    if (memcmp(file + 16, key, KEY_SIZE)) return "from another build";
    /* VkPipelineCacheHeaderVersionOne: headerSize, headerVersion, vendorID, deviceID, pipelineCacheUUID. */
    const unsigned char *d = file + HEADER_SIZE;
    if (data_size < 16 + VK_UUID_SIZE) return "truncated (no Vulkan cache header)";
    uint32_t header_size = read_u32(d), version = read_u32(d + 4);
    if (header_size < 16 + VK_UUID_SIZE || header_size > data_size || version != VK_PIPELINE_CACHE_HEADER_VERSION_ONE)
        return "not a Vulkan pipeline cache (header)";
    if (read_u32(d + 8) != props->vendorID || read_u32(d + 12) != props->deviceID ||
        memcmp(d + 16, props->pipelineCacheUUID, VK_UUID_SIZE))
        return "made for another device or driver";
    return NULL;
}

/* Reads the whole file (at most MAX_FILE bytes); NULL if absent or unreadable. */
static unsigned char *read_file(const char *path, size_t *size)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return NULL;
    struct stat st;
    unsigned char *buf = NULL;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size <= MAX_FILE) buf = malloc((size_t)st.st_size + 1);
    size_t got = 0;
    while (buf && got < (size_t)st.st_size) {
        ssize_t n = read(fd, buf + got, (size_t)st.st_size - got);
        if (n <= 0) break;
        got += (size_t)n;
    }
    close(fd);
    *size = got;
    return buf;
}

/* mkdir -p for the cache directory (~/.cache may not exist yet). */
static int make_dirs(const char *dir)
{
    char p[4096];
    if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) return -1;
    for (char *s = p + 1; *s; ++s) {
        if (*s != '/') continue;
        *s = 0;
        if (mkdir(p, 0755) != 0 && errno != EEXIST) return -1;
        *s = '/';
    }
    return mkdir(p, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

void gpu_pipeline_cache_open(gpu_context *ctx, const char *dir, const char *build_key)
{
    VkPipelineCacheCreateInfo info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    struct gpu_cache_file *f = dir ? calloc(1, sizeof *f) : NULL;
    unsigned char *file = NULL;
    if (f) {
        const uint8_t *u = ctx->props.pipelineCacheUUID;
        char uuid[2 * VK_UUID_SIZE + 1];
        for (unsigned i = 0; i < VK_UUID_SIZE; ++i) snprintf(uuid + 2 * i, 3, "%02x", u[i]);
        int n = snprintf(f->path, sizeof f->path, "%s/pipelines-%s-%08x.bin", dir, uuid, ctx->props.driverVersion);
        strncpy(f->key, build_key ? build_key : "", KEY_SIZE - 1);
        snprintf(f->dir, sizeof f->dir, "%s", dir);
        size_t size = 0;
        file = n > 0 && n < (int)sizeof f->path ? read_file(f->path, &size) : NULL;
        const char *why = file ? gpu_pipeline_cache_check(file, size, f->key, &ctx->props) : NULL;
        if (file && !why) {
            info.initialDataSize = size - HEADER_SIZE;
            info.pInitialData = file + HEADER_SIZE;
            f->loaded_size = info.initialDataSize;
            f->loaded_sum = read_u64(file + 56);
        } else if (why && strcmp(why, "from another build")) {
            /* A new build replaces the file without a word; anything else is worth one line. */
            gpu_report(ctx, 1, "pipeline cache %s: %s; ignored, it will be replaced", f->path, why);
        }
    }
    VK_CHECK(vkCreatePipelineCache(ctx->device, &info, gpu_allocator(ctx->device), &ctx->pipeline_cache));
    gpu_set_name(ctx, VK_OBJECT_TYPE_PIPELINE_CACHE, (uint64_t)ctx->pipeline_cache, "pipeline cache");
    free(file);
    ctx->cache_file = f;
}

/* Temporary file beside the target, then rename: a reader (another vksky starting now) sees the old file or the
 * new one, never half of one. No fsync: a file cut short by a crash fails the size or checksum check next time
 * and is replaced, which is all a cache needs. */
static int write_atomic(const char *path, const unsigned char *header, size_t header_size, const void *data,
                        size_t size)
{
    char dir[4096], tmp[4200];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = 0;
    if (slash && make_dirs(dir) != 0) return -1;
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    bool ok = write(fd, header, header_size) == (ssize_t)header_size && write(fd, data, size) == (ssize_t)size;
    ok = close(fd) == 0 && ok;
    if (ok && rename(tmp, path) == 0) return 0;
    int e = errno;
    unlink(tmp);
    errno = e;
    return -1;
}

static int save(const struct gpu_cache_file *f, const unsigned char *data, size_t size, uint64_t sum)
{
    unsigned char header[HEADER_SIZE] = {0};
    uint32_t version = 1;
    uint64_t size64 = size;
    memcpy(header, MAGIC, sizeof MAGIC);
    memcpy(header + 8, &version, 4);
    memcpy(header + 16, f->key, KEY_SIZE);
    memcpy(header + 48, &size64, 8);
    memcpy(header + 56, &sum, 8);
    return write_atomic(f->path, header, HEADER_SIZE, data, size);
}

void gpu_pipeline_cache_close(gpu_context *ctx)
{
    struct gpu_cache_file *f = ctx->cache_file;
    if (f && ctx->pipeline_cache) {
        size_t size = 0;
        unsigned char *data = NULL;
        if (vkGetPipelineCacheData(ctx->device, ctx->pipeline_cache, &size, NULL) == VK_SUCCESS && size > 0)
            data = malloc(size);
        if (data && vkGetPipelineCacheData(ctx->device, ctx->pipeline_cache, &size, data) == VK_SUCCESS) {
            uint64_t sum = fnv1a64(data, size);
            /* Nothing new (a warm run): leave the file alone. */
            bool same = size == f->loaded_size && sum == f->loaded_sum;
            if (!same && save(f, data, size, sum) != 0)
                gpu_report(ctx, 1, "pipeline cache not saved: %s: %s (the render is unaffected)", f->path,
                        strerror(errno));
        }
        free(data);
    }
    if (ctx->pipeline_cache) vkDestroyPipelineCache(ctx->device, ctx->pipeline_cache, gpu_allocator(ctx->device));
    ctx->pipeline_cache = VK_NULL_HANDLE;
    free(f);
    ctx->cache_file = NULL;
}

bool gpu_cache_dir_attach(gpu_context *ctx, const char *dir)
{
    free(ctx->cache_file);
    ctx->cache_file = NULL;
    if (!dir || !dir[0]) return true;
    struct gpu_cache_file *f = calloc(1, sizeof *f);
    if (!f || snprintf(f->dir, sizeof f->dir, "%s", dir) >= (int)sizeof f->dir) {
        free(f);
        return false;
    }
    ctx->cache_file = f;
    return true;
}

const char *gpu_cache_dir(const gpu_context *ctx)
{
    return ctx->cache_file && ctx->cache_file->dir[0] ? ctx->cache_file->dir : NULL;
}

/* --- Keyed blobs beside the pipeline cache (the LUT cache, issue 27) ---
 * <dir>/<name>-<device UUID>-<driver version>-<key hash>.bin: a header of ours (magic, version, the key's and the
 * payload's sizes, a checksum over key and payload), the caller's key bytes, the payload. Distinct keys get distinct
 * files (switching between two scenes keeps both); a file under a key's name must still hold that key byte for
 * byte. */
enum { BLOB_HEADER = 40 };
static const char BLOB_MAGIC[8] = {'V', 'K', 'S', 'K', 'Y', 'B', 'C', '1'};

static bool blob_path(const gpu_context *ctx, const char *name, const void *key, size_t key_size, char *path,
                      size_t cap)
{
    const struct gpu_cache_file *f = ctx->cache_file;
    if (!f || !f->dir[0]) return false;
    const uint8_t *u = ctx->props.pipelineCacheUUID;
    char uuid[2 * VK_UUID_SIZE + 1];
    for (unsigned i = 0; i < VK_UUID_SIZE; ++i) snprintf(uuid + 2 * i, 3, "%02x", u[i]);
    int n = snprintf(path, cap, "%s/%s-%s-%08x-%016llx.bin", f->dir, name, uuid, ctx->props.driverVersion,
                     (unsigned long long)fnv1a64(key, key_size));
    return n > 0 && (size_t)n < cap;
}

const char *gpu_cache_blob_check(const unsigned char *file, size_t size, const void *key, size_t key_size,
                                 size_t payload_size)
{
    if (size < sizeof BLOB_MAGIC || memcmp(file, BLOB_MAGIC, sizeof BLOB_MAGIC)) return "not a vksky cache file";
    if (size < BLOB_HEADER) return "truncated";
    if (read_u32(file + 8) != 1) return "of another version";
    uint64_t ksize = read_u64(file + 16), psize = read_u64(file + 24);
    if (ksize > size || psize > size || BLOB_HEADER + ksize + psize != size) return "truncated";
    if (fnv1a64(file + BLOB_HEADER, size - BLOB_HEADER) != read_u64(file + 32)) return "corrupt (checksum)";
    if (ksize != key_size || memcmp(file + BLOB_HEADER, key, key_size)) return "made for other inputs (key)";
    if (psize != payload_size) return "of another size";
    return NULL;
}

void *gpu_cache_blob_load(const gpu_context *ctx, const char *name, const void *key, size_t key_size,
                          size_t payload_size)
{
    char path[4400];
    if (!blob_path(ctx, name, key, key_size, path, sizeof path)) return NULL;
    size_t size = 0;
    unsigned char *file = read_file(path, &size);
    if (!file) return NULL;   /* absent: the first run, nothing to say */
    const char *why = gpu_cache_blob_check(file, size, key, key_size, payload_size);
    if (why) {
        gpu_report(ctx, 1, "cache file %s: %s; ignored, it will be replaced", path, why);
        free(file);
        return NULL;
    }
    memmove(file, file + BLOB_HEADER + key_size, payload_size);
    return file;
}

bool gpu_cache_blob_store(const gpu_context *ctx, const char *name, const void *key, size_t key_size,
                          const void *payload, size_t payload_size)
{
    char path[4400];
    if (!blob_path(ctx, name, key, key_size, path, sizeof path)) return false;
    size_t body = key_size + payload_size;
    unsigned char *buf = malloc(BLOB_HEADER + body);
    if (!buf) return false;
    memset(buf, 0, BLOB_HEADER);
    memcpy(buf, BLOB_MAGIC, sizeof BLOB_MAGIC);
    uint32_t version = 1;
    uint64_t ksize = key_size, psize = payload_size;
    memcpy(buf + 8, &version, 4);
    memcpy(buf + 16, &ksize, 8);
    memcpy(buf + 24, &psize, 8);
    memcpy(buf + BLOB_HEADER, key, key_size);
    memcpy(buf + BLOB_HEADER + key_size, payload, payload_size);
    uint64_t sum = fnv1a64(buf + BLOB_HEADER, body);
    memcpy(buf + 32, &sum, 8);
    int rc = write_atomic(path, buf, BLOB_HEADER, buf + BLOB_HEADER, body);
    if (rc != 0)
        gpu_report(ctx, 1, "cache file not saved: %s: %s (the render is unaffected)", path, strerror(errno));
    free(buf);
    return rc == 0;
}
