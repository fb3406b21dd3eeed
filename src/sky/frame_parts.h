/* What frame.c and frame_luts.c, the two halves of the frame spine, share: a timed, labelled pass, the image copy
 * of readbacks, and the LUT step every frame starts with. Nothing outside the frame functions includes it. */
#ifndef VKSKY_SKY_FRAME_PARTS_H
#define VKSKY_SKY_FRAME_PARTS_H
#include "sky/frame.h"

/* A pass: its debug label (gpu_label_begin also prints its `pass` trace line, the one pass trace) and timestamps. */
uint32_t frame_timed_begin(sky_renderer *r, VkCommandBuffer cmd, const char *pass);
void frame_timed_end(sky_renderer *r, VkCommandBuffer cmd, uint32_t slot);
/* Mip 0 of a colour image in TRANSFER_SRC_OPTIMAL copied, tightly packed, into `buffer`. */
void frame_copy_to_buffer(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer);
/* The LUTs, when their inputs changed (or `force`): their passes and barriers, the last one into `next`; first the
 * acquire of LUTs another family's compute queue released (--async-luts). */
void frame_record_luts_if_dirty(sky_renderer *r, VkCommandBuffer cmd, bool force, gpu_barrier_batch *next);
#endif
