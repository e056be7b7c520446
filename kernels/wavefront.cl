/*
 * wavefront.cl — the path integrator as wavefront stages (one program, one kernel each):
 *
 *   generate -> [ extend -> shade -> shadow ] x max_depth -> accumulate
 *
 * A pass renders samples_in_pass consecutive sample indices for a batch of pixels (several
 * only when the image is smaller than the wavefront). Path slot i * samples_in_pass + s owns
 * sample sample_index + s of the batch's pixel i (gc_batch_pixel) for the whole pass;
 * accumulate.cl adds
 * each pixel's samples in sample order. Queues hold slot indices (pushed as gc_queue.h says);
 * every stage is launched over the queue's capacity and returns early past the queue's
 * count, so the host never reads a counter mid-pass (pbrt-v4's WorkQueue scheme). Because
 * a path's random numbers depend only on (pixel, sample, bounce, dimension) and a slot is
 * written by one work-item per stage, the image does not depend on queue order: the same
 * device gives the same bits every run.
 */
#include "generate.cl"
#include "extend.cl"
#include "shade.cl"
#include "shadow.cl"
#include "accumulate.cl"
