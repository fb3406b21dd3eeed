/* The usage table and the barrier builder, without a GPU.
 *
 * Each named usage is checked against the Khronos synchronization2 examples ("Synchronization Examples" in
 * KhronosGroup/Vulkan-Docs' wiki, now chapters/synchronization_examples.adoc of KhronosGroup/Vulkan-Guide): the
 * stage, access and layout a scenario there uses for the same kind of access. Then the builder: the source side
 * carries only write accesses, a discard starts from UNDEFINED, every field lands where it belongs; the hazard
 * names; and the trace line format that tools/sync_doc.sh parses. No device is created: building a barrier and
 * adding it to a batch record nothing (only gpu_barrier_flush calls Vulkan). Also: buffer hazards, the one pass
 * trace, and each batch array's overflow check. */
#include "gpu/barrier.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "check.h"

/* Read access bits of synchronization2 (everything gpu_write_accesses must drop). */
static const VkAccessFlags2 READS = VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT |
                                    VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_UNIFORM_READ_BIT |
                                    VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_READ_BIT |
                                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
                                    VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_MEMORY_READ_BIT |
                                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;

static const char *usage_name(gpu_usage u) { return gpu_usage_get(u)->name; }

/* The layout a usage must have: `alt` is the equivalent generic sync2 layout the examples print
 * (READ_ONLY_OPTIMAL / ATTACHMENT_OPTIMAL), accepted as well. */
static void check_usage(gpu_usage u, VkPipelineStageFlags2 stage, VkAccessFlags2 access_any, VkAccessFlags2 access_all,
                        VkImageLayout layout, VkImageLayout alt, const char *example)
{
    const gpu_usage_info *i = gpu_usage_get(u);
    CHECK(i->stage == stage, "%s: stage 0x%llx, expected 0x%llx (%s)", i->name, (unsigned long long)i->stage,
          (unsigned long long)stage, example);
    /* access_all: bits that must all be there; access_any: bits the access must stay within (sync2 spells
     * some accesses two ways: SHADER_READ = SAMPLED_READ | STORAGE_READ, SHADER_WRITE = STORAGE_WRITE). */
    CHECK((i->access & access_all) == access_all, "%s: access 0x%llx lacks 0x%llx (%s)", i->name,
          (unsigned long long)i->access, (unsigned long long)access_all, example);
    CHECK((i->access & ~access_any) == 0, "%s: access 0x%llx has bits outside 0x%llx (%s)", i->name,
          (unsigned long long)i->access, (unsigned long long)access_any, example);
    CHECK(i->layout == layout || i->layout == alt, "%s: layout %s, expected %s (%s)", i->name,
          gpu_layout_name(i->layout), gpu_layout_name(layout), example);
}

static void test_usage_table(void)
{
    const VkAccessFlags2 shader_read = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    const VkAccessFlags2 shader_write = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    const VkImageLayout RO = VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL, ATT = VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL;
    const VkImageLayout NO_ALT = VK_IMAGE_LAYOUT_MAX_ENUM;

    check_usage(GPU_USAGE_NONE, VK_PIPELINE_STAGE_2_NONE, 0, 0, VK_IMAGE_LAYOUT_UNDEFINED, NO_ALT,
                "nothing before: no stage, no access, contents undefined");
    /* "Dispatch writes into a storage image. Draw samples that image in a fragment shader": src COMPUTE_SHADER
     * / SHADER_WRITE, old layout GENERAL ("storage image ... always in GENERAL layout"). */
    check_usage(GPU_USAGE_COMPUTE_STORAGE_WRITE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, shader_write, 0,
                VK_IMAGE_LAYOUT_GENERAL, NO_ALT, "dispatch writes a storage image");
    CHECK(gpu_write_accesses(gpu_usage_get(GPU_USAGE_COMPUTE_STORAGE_WRITE)->access) != 0,
          "compute_storage_write has no write access");
    /* ... dst FRAGMENT_SHADER / SHADER_READ, new layout READ_ONLY_OPTIMAL. */
    check_usage(GPU_USAGE_FRAGMENT_SAMPLED, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, shader_read, 0,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, RO, "draw samples an image in a fragment shader");
    /* "Draw writes to a color attachment. Dispatch samples from that image": dst COMPUTE_SHADER / SHADER_READ. */
    check_usage(GPU_USAGE_COMPUTE_SAMPLED, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, shader_read, 0,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, RO, "dispatch samples an image");
    check_usage(GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, shader_read, 0,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, RO, "sampled by a dispatch and a draw");
    /* "Note that color attachment write is NOT in the fragment shader, it has its own dedicated pipeline
     * stage": COLOR_ATTACHMENT_OUTPUT / COLOR_ATTACHMENT_WRITE, ATTACHMENT_OPTIMAL. */
    check_usage(GPU_USAGE_COLOR_ATTACHMENT_WRITE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, ATT, "draw writes a color attachment");
    /* Load op LOAD and blending read the attachment (the depth example's "load op ... dstAccessMask = ..._READ
     * | ..._WRITE", for colour): COLOR_ATTACHMENT_READ | COLOR_ATTACHMENT_WRITE. */
    check_usage(GPU_USAGE_COLOR_ATTACHMENT_BLEND, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, ATT, "LOAD + blending reads and writes the attachment");
    /* Copies: the examples use TRANSFER (COPY is its sync2 sub-stage for vkCmdCopy*) with TRANSFER_READ/WRITE. */
    check_usage(GPU_USAGE_TRANSFER_SRC, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, NO_ALT, "copy source");
    check_usage(GPU_USAGE_TRANSFER_DST, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, NO_ALT, "copy destination");
    /* "CPU read back of data written by a compute shader": dst HOST / HOST_READ, then the fence. */
    check_usage(GPU_USAGE_HOST_READ, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, NO_ALT, "CPU read back");
    /* "Swapchain Image Acquire and Present": the acquire semaphore is waited on at COLOR_ATTACHMENT_OUTPUT, the
     * first barrier has srcStage COLOR_ATTACHMENT_OUTPUT (same stage: chained after the wait), no src access,
     * old layout UNDEFINED. */
    check_usage(GPU_USAGE_ACQUIRED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                NO_ALT, "swapchain image acquired");
    /* Present: dst access 0 and layout PRESENT_SRC_KHR. dst stage NONE (or BOTTOM_OF_PIPE) is right because the
     * render-finished semaphore is signalled at ALL_COMMANDS (window.c submit()): the example's second
     * dependency (dst COLOR_ATTACHMENT_OUTPUT) "could be omitted" then. */
    const gpu_usage_info *p = gpu_usage_get(GPU_USAGE_PRESENT);
    CHECK(p->stage == VK_PIPELINE_STAGE_2_NONE || p->stage == VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT ||
              p->stage == VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
          "present: stage 0x%llx", (unsigned long long)p->stage);
    CHECK(p->access == 0, "present: access 0x%llx, expected 0", (unsigned long long)p->access);
    CHECK(p->layout == VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, "present: layout %s", gpu_layout_name(p->layout));

    for (int u = 0; u < GPU_USAGE_COUNT; ++u) {
        const gpu_usage_info *i = gpu_usage_get((gpu_usage)u);
        CHECK(i->name && *i->name, "usage %d has no name", u);
        /* An access needs a stage to happen in. */
        CHECK(i->access == 0 || i->stage != 0, "%s: access without a stage", usage_name((gpu_usage)u));
    }
}

static VkImageSubresourceRange mips(uint32_t base, uint32_t count)
{
    return (VkImageSubresourceRange){VK_IMAGE_ASPECT_COLOR_BIT, base, count, 0, 1};
}

/* One example scenario, built by gpu_image_barrier and compared field by field. */
static void check_barrier(const char *scenario, gpu_usage from, gpu_usage to, bool discard, VkPipelineStageFlags2 ss,
                          VkAccessFlags2 sa, VkPipelineStageFlags2 ds, VkAccessFlags2 da, VkImageLayout ol,
                          VkImageLayout nl)
{
    VkImageMemoryBarrier2 b = gpu_image_barrier((VkImage)(uintptr_t)0x1234, mips(2, 1), from, to, discard);
    CHECK(b.srcStageMask == ss, "%s: srcStageMask 0x%llx, expected 0x%llx", scenario, (unsigned long long)b.srcStageMask,
          (unsigned long long)ss);
    CHECK(b.srcAccessMask == sa, "%s: srcAccessMask 0x%llx, expected 0x%llx", scenario,
          (unsigned long long)b.srcAccessMask, (unsigned long long)sa);
    CHECK(b.dstStageMask == ds, "%s: dstStageMask 0x%llx, expected 0x%llx", scenario, (unsigned long long)b.dstStageMask,
          (unsigned long long)ds);
    CHECK(b.dstAccessMask == da, "%s: dstAccessMask 0x%llx, expected 0x%llx", scenario,
          (unsigned long long)b.dstAccessMask, (unsigned long long)da);
    CHECK(b.oldLayout == ol && b.newLayout == nl, "%s: layout %s -> %s, expected %s -> %s", scenario,
          gpu_layout_name(b.oldLayout), gpu_layout_name(b.newLayout), gpu_layout_name(ol), gpu_layout_name(nl));
}

static void test_example_barriers(void)
{
    const VkPipelineStageFlags2 CS = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, FS = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                CAO = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, COPY = VK_PIPELINE_STAGE_2_COPY_BIT;
    const VkAccessFlags2 SW = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, SR = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                         CAW = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, CAR = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
    const VkImageLayout GEN = VK_IMAGE_LAYOUT_GENERAL, RO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        ATT = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, UND = VK_IMAGE_LAYOUT_UNDEFINED;

    check_barrier("dispatch writes a storage image, draw samples it", GPU_USAGE_COMPUTE_STORAGE_WRITE,
                  GPU_USAGE_FRAGMENT_SAMPLED, false, CS, SW, FS, SR, GEN, RO);
    check_barrier("draw writes a colour attachment, dispatch samples it", GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                  GPU_USAGE_COMPUTE_SAMPLED, false, CAO, CAW, CS, SR, ATT, RO);
    check_barrier("draw writes a colour attachment, draw samples it", GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                  GPU_USAGE_FRAGMENT_SAMPLED, false, CAO, CAW, FS, SR, ATT, RO);
    /* "First draw samples a texture in the fragment shader. Second draw writes to that texture as a color
     * attachment": WAR, no src access; the layout transition is a write, so the dst access is set. */
    check_barrier("draw samples, next draw writes it as attachment (WAR)", GPU_USAGE_FRAGMENT_SAMPLED,
                  GPU_USAGE_COLOR_ATTACHMENT_WRITE, false, FS, 0, CAO, CAW, RO, ATT);
    check_barrier("... contents not needed (discard)", GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                  true, FS, 0, CAO, CAW, UND, ATT);
    check_barrier("sampled mip becomes the additive upsample's LOAD+blend target", GPU_USAGE_FRAGMENT_SAMPLED,
                  GPU_USAGE_COLOR_ATTACHMENT_BLEND, false, FS, 0, CAO, CAR | CAW, RO, ATT);
    check_barrier("upsample wrote the mip, the next upsample samples it", GPU_USAGE_COLOR_ATTACHMENT_BLEND,
                  GPU_USAGE_FRAGMENT_SAMPLED, false, CAO, CAW, FS, SR, ATT, RO);
    check_barrier("attachment written, copied out", GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false,
                  CAO, CAW, COPY, VK_ACCESS_2_TRANSFER_READ_BIT, ATT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    check_barrier("storage LUT sampled last frame, rewritten (WAR, discard)", GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED,
                  GPU_USAGE_COMPUTE_STORAGE_WRITE, true, CS | FS, 0, CS, SW, UND, GEN);
    /* Swapchain, the sync2 example's graphics-queue barrier verbatim: src COLOR_ATTACHMENT_OUTPUT, no src access,
     * dst COLOR_ATTACHMENT_OUTPUT / COLOR_ATTACHMENT_WRITE, UNDEFINED -> ATTACHMENT_OPTIMAL. */
    check_barrier("swapchain image acquired, tone map renders into it", GPU_USAGE_ACQUIRED,
                  GPU_USAGE_COLOR_ATTACHMENT_WRITE, true, CAO, 0, CAO, CAW, UND, ATT);
    const gpu_usage_info *p = gpu_usage_get(GPU_USAGE_PRESENT);
    check_barrier("tone map wrote the swapchain image, present it", GPU_USAGE_COLOR_ATTACHMENT_WRITE,
                  GPU_USAGE_PRESENT, false, CAO, CAW, p->stage, 0, ATT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    check_barrier("screenshot copied, present it", GPU_USAGE_TRANSFER_SRC, GPU_USAGE_PRESENT, false, COPY, 0,
                  p->stage, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);

    /* "CPU read back": a buffer barrier, COPY / TRANSFER_WRITE -> HOST / HOST_READ, whole buffer. */
    gpu_barrier_set_drop(NULL);
    gpu_barrier_batch batch = gpu_barrier_batch_begin("test");
    gpu_barrier_add_buffer(&batch, "t.to_host", "buf", (VkBuffer)(uintptr_t)0x99, GPU_USAGE_TRANSFER_DST,
                           GPU_USAGE_HOST_READ);
    CHECK(batch.buffer_count == 1 && batch.image_count == 0, "buffer barrier not batched");
    VkBufferMemoryBarrier2 bb = batch.buffers[0];
    CHECK(bb.srcStageMask == COPY && bb.srcAccessMask == VK_ACCESS_2_TRANSFER_WRITE_BIT, "to host: src wrong");
    CHECK(bb.dstStageMask == VK_PIPELINE_STAGE_2_HOST_BIT && bb.dstAccessMask == VK_ACCESS_2_HOST_READ_BIT,
          "to host: dst wrong");
    CHECK(bb.offset == 0 && bb.size == VK_WHOLE_SIZE && bb.buffer == (VkBuffer)(uintptr_t)0x99, "to host: range");
    CHECK(bb.srcQueueFamilyIndex == VK_QUEUE_FAMILY_IGNORED && bb.dstQueueFamilyIndex == VK_QUEUE_FAMILY_IGNORED,
          "to host: queue families");
}

/* Every pair of usages: the builder's invariants. */
static void test_builder_invariants(void)
{
    for (int f = 0; f < GPU_USAGE_COUNT; ++f)
        for (int t = 0; t < GPU_USAGE_COUNT; ++t)
            for (int d = 0; d < 2; ++d) {
                const gpu_usage_info *fi = gpu_usage_get((gpu_usage)f), *ti = gpu_usage_get((gpu_usage)t);
                VkImage img = (VkImage)(uintptr_t)0xabc;
                VkImageSubresourceRange r = mips(1, 3);
                VkImageMemoryBarrier2 b = gpu_image_barrier(img, r, (gpu_usage)f, (gpu_usage)t, d);
                const char *fn = fi->name, *tn = ti->name;
                CHECK(b.sType == VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2 && b.pNext == NULL, "%s->%s: sType", fn, tn);
                /* Source side: only writes (nothing to make available from a read), and all of them. */
                CHECK((b.srcAccessMask & READS) == 0, "%s->%s: read bits in srcAccessMask 0x%llx", fn, tn,
                      (unsigned long long)b.srcAccessMask);
                CHECK(b.srcAccessMask == gpu_write_accesses(fi->access), "%s->%s: srcAccessMask", fn, tn);
                CHECK(b.srcStageMask == fi->stage, "%s->%s: srcStageMask", fn, tn);
                CHECK(b.dstStageMask == ti->stage && b.dstAccessMask == ti->access, "%s->%s: dst side", fn, tn);
                CHECK(b.oldLayout == (d ? VK_IMAGE_LAYOUT_UNDEFINED : fi->layout), "%s->%s discard=%d: oldLayout %s",
                      fn, tn, d, gpu_layout_name(b.oldLayout));
                CHECK(b.newLayout == ti->layout, "%s->%s: newLayout", fn, tn);
                CHECK(b.srcQueueFamilyIndex == VK_QUEUE_FAMILY_IGNORED &&
                          b.dstQueueFamilyIndex == VK_QUEUE_FAMILY_IGNORED,
                      "%s->%s: queue family ownership transfer", fn, tn);
                CHECK(b.image == img && memcmp(&b.subresourceRange, &r, sizeof r) == 0, "%s->%s: image/range", fn,
                      tn);
            }
    /* gpu_write_accesses keeps exactly the writes. */
    CHECK(gpu_write_accesses(READS) == 0, "reads kept: 0x%llx", (unsigned long long)gpu_write_accesses(READS));
    const VkAccessFlags2 writes = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                  VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |
                                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    CHECK(gpu_write_accesses(writes | READS) == writes, "writes lost: 0x%llx",
          (unsigned long long)gpu_write_accesses(writes | READS));
}

static void check_hazard(gpu_usage from, gpu_usage to, bool discard, const char *want)
{
    char buf[32];
    const char *got = gpu_hazard_name(from, to, discard, buf, sizeof buf);
    CHECK(strcmp(got, want) == 0, "%s -> %s%s: hazard %s, expected %s", usage_name(from), usage_name(to),
          discard ? " (discard)" : "", got, want);
}

static void test_hazard_names(void)
{
    char buf[40];
    /* Read after write: the source wrote, the destination reads. */
    check_hazard(GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, false, "RAW+layout");
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_FRAGMENT_SAMPLED, false, "RAW+layout");
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_TRANSFER_SRC, false, "RAW+layout");
    /* Buffers and global barriers: no layout. */
    CHECK(strcmp(gpu_hazard_name_nolayout(GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ, buf, sizeof buf), "RAW") == 0,
          "copy -> host (buffer): %s, expected RAW", buf);
    CHECK(strcmp(gpu_hazard_name_nolayout(GPU_USAGE_TRANSFER_DST, GPU_USAGE_TRANSFER_DST, buf, sizeof buf), "WAW") == 0,
          "copy -> copy (buffer, VKSKY_FRAMES): %s, expected WAW", buf);
    /* Read-write usages: every hazard that applies, in the order RAW, WAR, WAW (the source reads as well as
     * writes, so a write after it is also a write-after-read). */
    CHECK(strcmp(gpu_hazard_name_nolayout(GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW, buf, sizeof buf),
                 "RAW+WAR+WAW") == 0, "rw -> rw (global): %s, expected RAW+WAR+WAW", buf);
    check_hazard(GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_CLEAR_DST, true, "WAR+WAW+layout");
    check_hazard(GPU_USAGE_CLEAR_DST, GPU_USAGE_COMPUTE_STORAGE_RW, false, "RAW+WAW");
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_BLEND, GPU_USAGE_FRAGMENT_SAMPLED, false, "RAW+layout");
    /* The presentation engine reads what the tone map wrote. */
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_PRESENT, false, "RAW+layout");
    /* Write after read: the source only read, the destination writes. */
    check_hazard(GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true, "WAR+layout");
    check_hazard(GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_STORAGE_WRITE, true, "WAR+layout");
    check_hazard(GPU_USAGE_TRANSFER_SRC, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true, "WAR+layout");
    check_hazard(GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COLOR_ATTACHMENT_BLEND, false, "WAR+layout");
    check_hazard(GPU_USAGE_ACQUIRED, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true, "WAR+layout");
    /* Write after write: both write, the destination does not read. */
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_COLOR_ATTACHMENT_WRITE, false, "WAW");
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_COLOR_ATTACHMENT_WRITE, true, "WAW+layout");
    check_hazard(GPU_USAGE_TRANSFER_DST, GPU_USAGE_TRANSFER_DST, false, "WAW");
    /* The destination reads and writes what the source wrote (LOAD + blend after a write). */
    check_hazard(GPU_USAGE_COLOR_ATTACHMENT_WRITE, GPU_USAGE_COLOR_ATTACHMENT_BLEND, false, "RAW+WAW");
    /* Reads on both sides: no hazard, at most a layout transition. */
    check_hazard(GPU_USAGE_FRAGMENT_SAMPLED, GPU_USAGE_COMPUTE_SAMPLED, false, "none");
    check_hazard(GPU_USAGE_TRANSFER_SRC, GPU_USAGE_PRESENT, false, "layout");
    check_hazard(GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, GPU_USAGE_TRANSFER_SRC, false, "layout");
    /* Nothing before: no earlier access to order against, only the transition. */
    check_hazard(GPU_USAGE_NONE, GPU_USAGE_COMPUTE_STORAGE_WRITE, true, "layout");
    check_hazard(GPU_USAGE_NONE, GPU_USAGE_COLOR_ATTACHMENT_WRITE, false, "layout");
}

/* The trace line that tools/sync_doc.sh and tests/barrier_drop_test.sh parse, and the drop switch. */
static void test_trace_and_drop(void)
{
    FILE *f = tmpfile();
    CHECK(f != NULL, "tmpfile");
    if (!f) return;
    gpu_barrier_trace(f);
    gpu_barrier_set_drop("t.dropped");
    unsigned before = gpu_barrier_dropped_count();
    gpu_barrier_trace_pass("some_pass");
    gpu_barrier_batch b = gpu_barrier_batch_begin("after some pass");
    gpu_barrier_add_image(&b, "t.kept", "img", (VkImage)(uintptr_t)1, mips(0, 5), GPU_USAGE_FRAGMENT_SAMPLED,
                          GPU_USAGE_COLOR_ATTACHMENT_WRITE, true);
    gpu_barrier_add_image(&b, "t.dropped", "img", (VkImage)(uintptr_t)1, mips(3, 1), GPU_USAGE_COLOR_ATTACHMENT_BLEND,
                          GPU_USAGE_FRAGMENT_SAMPLED, false);
    gpu_barrier_add_buffer(&b, "t.buffer", "buf", (VkBuffer)(uintptr_t)2, GPU_USAGE_TRANSFER_DST, GPU_USAGE_HOST_READ);
    gpu_barrier_trace(NULL);
    gpu_barrier_set_drop(NULL);
    CHECK(b.image_count == 1 && b.buffer_count == 1, "batch holds %u images, %u buffers; expected 1, 1",
          b.image_count, b.buffer_count);
    CHECK(gpu_barrier_dropped_count() == before + 1, "dropped count %u, expected %u", gpu_barrier_dropped_count(),
          before + 1);

    char text[2048] = {0};
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    const char *want =
        "pass some_pass\n"
        "barrier t.kept point=after some pass resource=img mips=0-4 layout=UNDEFINED->COLOR_ATTACHMENT_OPTIMAL "
        "src=FRAGMENT_SHADER/NONE dst=COLOR_ATTACHMENT_OUTPUT/COLOR_ATTACHMENT_WRITE hazard=WAR+layout\n"
        "barrier t.dropped point=after some pass resource=img mips=3 layout=COLOR_ATTACHMENT_OPTIMAL->"
        "SHADER_READ_ONLY_OPTIMAL src=COLOR_ATTACHMENT_OUTPUT/COLOR_ATTACHMENT_WRITE "
        "dst=FRAGMENT_SHADER/SHADER_SAMPLED_READ hazard=RAW+layout DROPPED\n"
        "barrier t.buffer point=after some pass resource=buf mips=- layout=UNDEFINED->UNDEFINED "
        "src=COPY/TRANSFER_WRITE dst=HOST/HOST_READ hazard=RAW\n";
    CHECK(strcmp(text, want) == 0, "trace:\n%s\nexpected:\n%s", text, want);

    /* Stage and access strings join bits with '|' (the trace and the guide's tables split on it). */
    char s[128];
    gpu_stage_string(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, s, sizeof s);
    CHECK(strcmp(s, "COMPUTE_SHADER|FRAGMENT_SHADER") == 0, "stage string %s", s);
    gpu_access_string(VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, s, sizeof s);
    CHECK(strcmp(s, "COLOR_ATTACHMENT_READ|COLOR_ATTACHMENT_WRITE") == 0, "access string %s", s);
    gpu_stage_string(0, s, sizeof s);
    CHECK(strcmp(s, "NONE") == 0, "empty stage string %s", s);
}

/* The mask mutation (VKSKY_WEAKEN_BARRIER) and the global barrier: what the trace shows, what the batch holds. */
static void test_weaken_and_memory(void)
{
    char why[200];
    CHECK(!gpu_barrier_set_weaken("nocolon", why, sizeof why), "a spec without ':' accepted");
    CHECK(!gpu_barrier_set_weaken("x:srcmask", why, sizeof why), "an unknown field accepted");
    CHECK(!gpu_barrier_set_weaken("x:dstaccess=BOGUS", why, sizeof why), "an unknown access accepted");
    CHECK(!gpu_barrier_set_weaken("x:srcstage=SHADER_SAMPLED_READ", why, sizeof why), "an access as a stage accepted");
    CHECK(gpu_barrier_set_weaken(NULL, why, sizeof why), "NULL refused");

    FILE *f = tmpfile();
    CHECK(f != NULL, "tmpfile");
    if (!f) return;
    gpu_barrier_trace(f);
    unsigned before = gpu_barrier_weakened_count();
    gpu_barrier_batch b = gpu_barrier_batch_begin("p");
    /* Classic mistake 3: the blend's read left out of the destination. */
    CHECK(gpu_barrier_set_weaken("t.blend:dstaccess=COLOR_ATTACHMENT_WRITE", why, sizeof why), "%s", why);
    gpu_barrier_add_image(&b, "t.blend", "img", (VkImage)(uintptr_t)1, mips(2, 1), GPU_USAGE_FRAGMENT_SAMPLED,
                          GPU_USAGE_COLOR_ATTACHMENT_BLEND, false);
    /* A source stage weakened to NONE takes the source access with it. */
    CHECK(gpu_barrier_set_weaken("t.mem:srcstage", why, sizeof why), "%s", why);
    gpu_barrier_add_memory(&b, "t.mem", "chain", GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW);
    gpu_barrier_set_weaken(NULL, why, sizeof why);
    gpu_barrier_add_memory(&b, "t.mem2", "chain", GPU_USAGE_COMPUTE_STORAGE_WRITE, GPU_USAGE_COMPUTE_SAMPLED);
    gpu_barrier_trace(NULL);
    CHECK(gpu_barrier_weakened_count() == before + 2, "weakened %u, expected %u", gpu_barrier_weakened_count(),
          before + 2);
    CHECK(b.image_count == 1 && b.memory_count == 2, "batch holds %u images, %u memory barriers", b.image_count,
          b.memory_count);
    CHECK(b.images[0].dstAccessMask == VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "weakened dst access 0x%llx",
          (unsigned long long)b.images[0].dstAccessMask);
    CHECK(b.memory[0].srcStageMask == 0 && b.memory[0].srcAccessMask == 0, "srcstage NONE kept an access");
    CHECK(b.memory[1].sType == VK_STRUCTURE_TYPE_MEMORY_BARRIER_2 &&
              b.memory[1].srcStageMask == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT &&
              b.memory[1].srcAccessMask == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT &&
              b.memory[1].dstAccessMask == VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
          "global barrier fields");
    char text[2048] = {0};
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    const char *want =
        "barrier t.blend point=p resource=img mips=2 layout=SHADER_READ_ONLY_OPTIMAL->COLOR_ATTACHMENT_OPTIMAL "
        "src=FRAGMENT_SHADER/NONE dst=COLOR_ATTACHMENT_OUTPUT/COLOR_ATTACHMENT_WRITE hazard=WAR+layout "
        "WEAKENED=dstaccess\n"
        "barrier t.mem point=p resource=chain mips=* layout=UNDEFINED->UNDEFINED src=NONE/NONE "
        "dst=COMPUTE_SHADER/SHADER_STORAGE_READ|SHADER_STORAGE_WRITE|SHADER_SAMPLED_READ hazard=RAW+WAR+WAW "
        "WEAKENED=srcstage\n"
        "barrier t.mem2 point=p resource=chain mips=* layout=UNDEFINED->UNDEFINED "
        "src=COMPUTE_SHADER/SHADER_STORAGE_WRITE dst=COMPUTE_SHADER/SHADER_SAMPLED_READ hazard=RAW\n";
    CHECK(strcmp(text, want) == 0, "trace:\n%s\nexpected:\n%s", text, want);
}

/* A buffer barrier's hazard is computed from its two usages like an image's (no layout): the readback buffer that
 * the next frame's copy rewrites is write-after-write, a copy source then rewritten is write-after-read. */
static void test_buffer_hazards(void)
{
    FILE *f = tmpfile();
    CHECK(f != NULL, "tmpfile");
    if (!f) return;
    gpu_barrier_trace(f);
    gpu_barrier_batch b = gpu_barrier_batch_begin("p");
    gpu_barrier_add_buffer(&b, "t.waw", "buf", (VkBuffer)(uintptr_t)2, GPU_USAGE_TRANSFER_DST, GPU_USAGE_TRANSFER_DST);
    gpu_barrier_add_buffer(&b, "t.war", "buf", (VkBuffer)(uintptr_t)2, GPU_USAGE_TRANSFER_SRC, GPU_USAGE_TRANSFER_DST);
    gpu_barrier_trace(NULL);
    CHECK(b.buffer_count == 2, "batch holds %u buffers, expected 2", b.buffer_count);
    CHECK(b.buffers[0].srcAccessMask == VK_ACCESS_2_TRANSFER_WRITE_BIT &&
              b.buffers[0].dstAccessMask == VK_ACCESS_2_TRANSFER_WRITE_BIT,
          "WAW barrier masks src 0x%llx dst 0x%llx", (unsigned long long)b.buffers[0].srcAccessMask,
          (unsigned long long)b.buffers[0].dstAccessMask);
    CHECK(b.buffers[1].srcAccessMask == 0, "a read contributed a source access");
    char text[1024] = {0};
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    CHECK(strstr(text, "barrier t.waw ") && strstr(strstr(text, "barrier t.waw "), "hazard=WAW\n"),
          "the copy-after-copy buffer barrier is not traced as WAW:\n%s", text);
    CHECK(strstr(text, "barrier t.war ") && strstr(strstr(text, "barrier t.war "), "hazard=WAR\n"),
          "the copy-source-then-rewritten buffer barrier is not traced as WAR:\n%s", text);
}

/* One pass trace: a pass line is printed once, into the barrier trace when it is on (even when the pass list is
 * on too, into the same stream), else into the pass list's stream; barrier lines never go to the pass list. */
static void test_one_pass_trace(void)
{
    FILE *f = tmpfile();
    CHECK(f != NULL, "tmpfile");
    if (!f) return;
    gpu_barrier_trace(f);
    gpu_barrier_trace_passes(f);
    gpu_barrier_trace_pass("both_on");
    gpu_barrier_trace(NULL);
    gpu_barrier_trace_pass("passes_only");
    gpu_barrier_batch b = gpu_barrier_batch_begin("p");
    gpu_barrier_add_memory(&b, "t.not_in_pass_list", "x", GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW);
    gpu_barrier_trace_passes(NULL);
    gpu_barrier_trace_pass("all_off");
    char text[512] = {0};
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    CHECK(strcmp(text, "pass both_on\npass passes_only\n") == 0, "pass trace:\n%s", text);
}

/* Each of a batch's arrays stops at its capacity with one line on stderr naming the batch, never writing past it
 * (run in a child: the overflow ends the process). kind 0 images, 1 buffers, 2 global barriers. */
static void overflow_child(int kind, uint32_t count)
{
    gpu_barrier_batch b = gpu_barrier_batch_begin("overflowing point");
    for (uint32_t i = 0; i < count; ++i) {
        if (kind == 0)
            gpu_barrier_add_image(&b, "t.img", "img", (VkImage)(uintptr_t)1, mips(0, 1), GPU_USAGE_COMPUTE_STORAGE_WRITE,
                                  GPU_USAGE_COMPUTE_SAMPLED, false);
        else if (kind == 1)
            gpu_barrier_add_buffer(&b, "t.buf", "buf", (VkBuffer)(uintptr_t)2, GPU_USAGE_TRANSFER_DST,
                                   GPU_USAGE_HOST_READ);
        else
            gpu_barrier_add_memory(&b, "t.mem", "x", GPU_USAGE_COMPUTE_STORAGE_RW, GPU_USAGE_COMPUTE_STORAGE_RW);
    }
    uint32_t held = kind == 0 ? b.image_count : kind == 1 ? b.buffer_count : b.memory_count;
    _exit(held == count ? 0 : 3);
}

static void test_batch_overflow(void)
{
    const uint32_t capacity[3] = {GPU_BATCH_MAX, (uint32_t)(sizeof((gpu_barrier_batch){0}.buffers) / sizeof(VkBufferMemoryBarrier2)),
                                  (uint32_t)(sizeof((gpu_barrier_batch){0}.memory) / sizeof(VkMemoryBarrier2))};
    const char *what[3] = {"images", "buffers", "global barriers"};
    for (int kind = 0; kind < 3; ++kind) {
        for (int over = 0; over < 2; ++over) {
            char path[] = "/tmp/vksky_overflow_XXXXXX";
            int fd = mkstemp(path);
            CHECK(fd >= 0, "mkstemp");
            if (fd < 0) return;
            fflush(NULL);
            pid_t pid = fork();
            if (pid == 0) {
                dup2(fd, 2);
                overflow_child(kind, capacity[kind] + (uint32_t)over);
            }
            int status = 0;
            waitpid(pid, &status, 0);
            char err[512] = {0};
            ssize_t n = pread(fd, err, sizeof err - 1, 0);
            close(fd);
            unlink(path);
            if (n < 0) n = 0;
            err[n] = 0;
            int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            if (!over)
                CHECK(code == 0 && !err[0], "%u %s (the capacity) did not fit: exit %d, stderr '%s'", capacity[kind],
                      what[kind], code, err);
            else
                CHECK(code == 1 && strstr(err, "internal error") && strstr(err, "'overflowing point'") &&
                          strchr(err, '\n') && !strchr(err, '\n')[1],
                      "%u %s (one over the capacity): exit %d (expected 1), stderr '%s' (expected one line naming "
                      "the batch)", capacity[kind] + 1, what[kind], code, err);
        }
    }
}

int main(void)
{
    test_usage_table();
    test_example_barriers();
    test_builder_invariants();
    test_hazard_names();
    test_trace_and_drop();
    test_weaken_and_memory();
    test_buffer_hazards();
    test_one_pass_trace();
    test_batch_overflow();
    if (check_failures) {
        fprintf(stderr, "test_barrier_table: %d failure(s)\n", check_failures);
        return 1;
    }
    printf("test_barrier_table: ok\n");
    return 0;
}
