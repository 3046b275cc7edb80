/* test_launch_shape.c - the launch shape of the long-looping kernels (throughput, the physically
 * based table, render) on CPU and GPU devices (host/core/clsession.c, no device needed). A group
 * of one work-item on a GPU runs one lane of a 32-lane warp: the NVIDIA H200 measured 2.04e12
 * flop/s with it, 1/32 of its float peak. Expected values worked by hand:
 *   - CPU device: groups of 1 (PoCL and llvmpipe spread groups over threads);
 *   - GPU: the largest of 256, 128, 64, 32 dividing the global size: 65536 -> 256, 67584 = 264 x 256
 *     -> 256, 96 = 3 x 32 -> 32 (96 / 64 is not whole), 100 -> none (the driver chooses: NULL);
 *   - default work-items: 32 per compute unit on a CPU (2 units: 64), 512 per unit elsewhere
 *     (16 units: 8192; 132 units: 67584, capped at 65536 by the throughput limit);
 *   - render: 256 on a CPU, 512 per compute unit on a GPU (132 units: 67584);
 *   - the accuracy sweep's chunks per n: 1 on a CPU; on a GPU of 132 units (target 67584
 *     work-items), 500 values of n with 16384 samples: doubled while 500 k < 67584 and a chunk
 *     keeps at least 256 samples: 64 (128 would leave 128 samples); 999 values with 4096
 *     samples: 16 (32 would leave 128);
 *   - the merge of chunk maxima, records written here by hand: the larger wins with its
 *     position, a tie keeps the earlier chunk's position, a NaN never wins, invalid counts add,
 *     the invalid position is the smallest s of any chunk (0.6 of 0.6 and 0.8; NaN is none). */
#include "check.h"
#include "clsession.h"
#include "render_report.h"
#include "accuracy.h"
#include "brdf_shared.h"

#include <math.h>

#include <string.h>

int main(void)
{
    struct cl_session cpu, gpu, small;
    memset(&cpu, 0, sizeof cpu);
    memset(&gpu, 0, sizeof gpu);
    memset(&small, 0, sizeof small);
    cpu.is_cpu = 1;
    cpu.compute_units = 2;
    gpu.is_cpu = 0;
    gpu.compute_units = 132;
    small.is_cpu = 0;
    small.compute_units = 16;

    CHECK_CASE("group size");
    size_t local = 99;
    const size_t *lp = clsession_group_size(&cpu, 64, &local);
    CHECK(lp == &local && local == 1, "CPU: group of 1 (got %zu)", local);
    lp = clsession_group_size(&gpu, 65536, &local);
    CHECK(lp == &local && local == 256, "GPU 65536: 256 (got %zu)", local);
    lp = clsession_group_size(&gpu, 67584, &local);
    CHECK(lp == &local && local == 256, "GPU 67584: 256 (got %zu)", local);
    lp = clsession_group_size(&gpu, 96, &local);
    CHECK(lp == &local && local == 32, "GPU 96: 32 (got %zu)", local);
    lp = clsession_group_size(&gpu, 100, &local);
    CHECK(lp == NULL, "GPU 100: the driver chooses (NULL)");

    CHECK_CASE("default work-items");
    CHECK(clsession_default_work_items(&cpu, 65536) == 64, "CPU, 2 units: 64 (got %ld)",
          clsession_default_work_items(&cpu, 65536));
    CHECK(clsession_default_work_items(&small, 65536) == 8192, "GPU, 16 units: 8192 (got %ld)",
          clsession_default_work_items(&small, 65536));
    CHECK(clsession_default_work_items(&gpu, 65536) == 65536, "GPU, 132 units: capped at 65536 (got %ld)",
          clsession_default_work_items(&gpu, 65536));

    CHECK_CASE("render");
    CHECK(render_work_items(&cpu) == 256, "render on a CPU: 256 (got %ld)", render_work_items(&cpu));
    CHECK(render_work_items(&gpu) == 67584, "render on a GPU of 132 units: 67584 (got %ld)", render_work_items(&gpu));

    CHECK_CASE("accuracy sweep chunks");
    CHECK(sweep_chunks(&cpu, 500, 16384) == 1, "CPU: 1 (got %ld)", sweep_chunks(&cpu, 500, 16384));
    CHECK(sweep_chunks(&gpu, 500, 16384) == 64, "GPU, 500 n, 16384 samples: 64 (got %ld)", sweep_chunks(&gpu, 500, 16384));
    CHECK(sweep_chunks(&gpu, 999, 4096) == 16, "GPU, 999 n, 4096 samples: 16 (got %ld)", sweep_chunks(&gpu, 999, 4096));

    CHECK_CASE("merge of chunk maxima");
    /* one n, three chunks: {epi_rel, s, att_abs, s, epi_abs, s, invalid count, first invalid s} */
    const float chunked[3 * ACC_OUT_STRIDE] = {
        0.5f, 0.01f, 2.0f, 0.3f, NAN, 0.0f, 0.0f, NAN,
        0.7f, 0.02f, 2.0f, 0.4f, 1.0f, 0.05f, 3.0f, 0.6f,
        0.6f, 0.03f, 1.5f, 0.5f, 4.0f, 0.07f, 2.0f, 0.8f,
    };
    float merged[ACC_OUT_STRIDE];
    accuracy_merge_chunks(chunked, 1, 3, merged);
    CHECK(merged[0] == 0.7f && merged[1] == 0.02f, "epicentre delta: chunk 1's 0.7 at 0.02 (got %g at %g)", merged[0],
          merged[1]);
    CHECK(merged[2] == 2.0f && merged[3] == 0.3f, "attenuation tie: chunk 0's position 0.3 (got %g at %g)", merged[2],
          merged[3]);
    CHECK(merged[4] == 4.0f && merged[5] == 0.07f, "NaN never wins: 4 at 0.07 (got %g at %g)", merged[4], merged[5]);
    CHECK(merged[6] == 5.0f, "invalid counts add: 5 (got %g)", merged[6]);
    CHECK(merged[7] == 0.6f, "invalid position: the smallest, 0.6 (got %g)", merged[7]);
    return check_summary();
}
