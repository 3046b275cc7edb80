/* test_launch_shape.c - the launch shape of the long-looping kernels (throughput, the physically
 * based table, render) on CPU and GPU devices (host/core/clsession.c, no device needed). A group
 * of one work-item on a GPU runs one lane of a 32-lane warp: the NVIDIA H200 measured 2.04e12
 * flop/s with it, 1/32 of its float peak. Expected values worked by hand:
 *   - CPU device: groups of 1 (PoCL and llvmpipe spread groups over threads);
 *   - GPU: the largest of 256, 128, 64, 32 dividing the global size: 65536 -> 256, 67584 = 264 x 256
 *     -> 256, 96 = 3 x 32 -> 32 (96 / 64 is not whole), 100 -> none (the driver chooses: NULL);
 *   - default work-items: 32 per compute unit on a CPU (2 units: 64), 512 per unit elsewhere
 *     (16 units: 8192; 132 units: 67584, capped at 65536 by the throughput limit);
 *   - render: 256 on a CPU, 512 per compute unit on a GPU (132 units: 67584). */
#include "check.h"
#include "clsession.h"
#include "render_report.h"

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
    return check_summary();
}
