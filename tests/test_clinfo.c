/* test_clinfo.c - the checked information queries and the kernel-argument helper of
 * host/core/clsession.c, on the first OpenCL device: a string query into a buffer shorter than
 * the string gives its head, NUL-terminated (compared with the plain clGetDeviceInfo call made
 * here); a number matches the plain call; a query of no device fails with the buffer empty and
 * the number zeroed; CL_SET_ARGS sets a kernel's arguments in order (the kernel, written here,
 * stores its second argument through its first, read back) and stops at an argument of the wrong
 * size with CL_INVALID_ARG_SIZE, naming the kernel, the argument's index and the error
 * (CL_SET_ARGS_WHY; CL_SET_ARGS_GOTO's line on stderr and its exit code 3). */
#include "check.h"
#include "clsession.h"
#include "exitcodes.h"

#include <string.h>

/* CL_SET_ARGS_GOTO in a function of the project's shape: 0, or EXIT_RUNTIME with its line on
   stderr (ctest shows it) when x's size is not the kernel's second argument's. */
#define set_wrong(k, out, x) set_args_goto((k), (out), &(x), sizeof(x))
static int set_args_goto(cl_kernel k, cl_mem out, const void *x, size_t size)
{
    int rc = 0;
    cl_uint i = 0;
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(out), ((struct cl_arg){ size, x }), CL_ARG(i));
done:
    return rc;
}

int main(void)
{
    struct cl_session s;
    char err[1024];
    int rc = clsession_open(&s, -1, -1, err, sizeof err);
    if (rc == EXIT_NO_DEVICE) {
        printf("no OpenCL device: %s\n", err);
        return check_summary_skipped();
    }
    CHECK(rc == 0, "clsession_open: %s", err);
    if (rc)
        return check_summary();

    CHECK_CASE("strings");
    char full[1024] = "", head[8];
    CHECK(clGetDeviceInfo(s.device, CL_DEVICE_NAME, sizeof full, full, NULL) == CL_SUCCESS, "plain query");
    CHECK(cl_device_string(s.device, CL_DEVICE_NAME, head, sizeof head) == CL_SUCCESS, "short buffer: success");
    size_t want = strlen(full) < sizeof head - 1 ? strlen(full) : sizeof head - 1;
    CHECK(strlen(head) == want && strncmp(head, full, want) == 0, "head '%s' of '%s'", head, full);
    char whole[1024];
    CHECK(cl_device_string(s.device, CL_DEVICE_NAME, whole, sizeof whole) == CL_SUCCESS && strcmp(whole, full) == 0,
          "whole name '%s'", whole);
    char pname[256];
    CHECK(cl_platform_string(s.platform, CL_PLATFORM_NAME, pname, sizeof pname) == CL_SUCCESS &&
              strcmp(pname, s.platform_name) == 0,
          "platform '%s'", pname);

    CHECK_CASE("numbers");
    cl_uint cu = 0, cu_plain = 0;
    CHECK(clGetDeviceInfo(s.device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu_plain, &cu_plain, NULL) == CL_SUCCESS,
          "plain query");
    CHECK(cl_device_value(s.device, CL_DEVICE_MAX_COMPUTE_UNITS, &cu, sizeof cu) == CL_SUCCESS && cu == cu_plain,
          "%u compute units, plainly %u", cu, cu_plain);

    CHECK_CASE("failures");
    char none[16] = "stale";
    CHECK(cl_device_string(NULL, CL_DEVICE_NAME, none, sizeof none) != CL_SUCCESS && none[0] == '\0',
          "no device: '%s'", none);
    cl_ulong mem = 12345;
    CHECK(cl_device_value(NULL, CL_DEVICE_GLOBAL_MEM_SIZE, &mem, sizeof mem) != CL_SUCCESS && mem == 0,
          "no device: %llu", (unsigned long long)mem);

    CHECK_CASE("kernel arguments");
    static const char *src = "__kernel void put(__global float *out, float v, uint i) { out[i] = v; }";
    cl_int e;
    cl_program prog = clCreateProgramWithSource(s.ctx, 1, &src, NULL, &e);
    CHECK(e == CL_SUCCESS, "program: %s", cl_error_name(e));
    e = clBuildProgram(prog, 1, &s.device, "", NULL, NULL);
    CHECK(e == CL_SUCCESS, "build: %s", cl_error_name(e));
    cl_kernel k = clCreateKernel(prog, "put", &e);
    CHECK(e == CL_SUCCESS, "kernel: %s", cl_error_name(e));
    cl_mem out = clCreateBuffer(s.ctx, CL_MEM_READ_WRITE, 4 * sizeof(float), NULL, &e);
    CHECK(e == CL_SUCCESS, "buffer: %s", cl_error_name(e));
    float zero[4] = { 0, 0, 0, 0 }, got[4] = { -1, -1, -1, -1 };
    clEnqueueWriteBuffer(s.queue, out, CL_TRUE, 0, sizeof zero, zero, 0, NULL, NULL);
    float v = 2.5f;
    cl_uint i = 2;
    e = CL_SET_ARGS(k, 0, CL_ARG(out), CL_ARG(v), CL_ARG(i));
    CHECK(e == CL_SUCCESS, "CL_SET_ARGS: %s", cl_error_name(e));
    size_t one = 1;
    CHECK(clEnqueueNDRangeKernel(s.queue, k, 1, NULL, &one, NULL, 0, NULL, NULL) == CL_SUCCESS, "launch");
    CHECK(clEnqueueReadBuffer(s.queue, out, CL_TRUE, 0, sizeof got, got, 0, NULL, NULL) == CL_SUCCESS, "read");
    CHECK(got[0] == 0 && got[1] == 0 && got[2] == 2.5f && got[3] == 0, "out = %g %g %g %g (2.5 at index 2)", got[0],
          got[1], got[2], got[3]);
    double wrong = 1;   /* the second argument is a float: 8 bytes are refused */
    e = CL_SET_ARGS(k, 0, CL_ARG(out), CL_ARG(wrong), CL_ARG(i));
    CHECK(e == CL_INVALID_ARG_SIZE, "a double for a float: %s", cl_error_name(e));
    e = CL_SET_ARGS(k, 1, CL_ARG(v), CL_ARG(i));   /* from the second argument on */
    CHECK(e == CL_SUCCESS, "from argument 1: %s", cl_error_name(e));
    /* the words of a failure: the kernel's name "put" (the source above), argument 1 (the float),
       CL_INVALID_ARG_SIZE, whose code is -51 in CL/cl.h */
    char why[256] = "";
    e = CL_SET_ARGS_WHY(k, 0, why, sizeof why, CL_ARG(out), CL_ARG(wrong), CL_ARG(i));
    CHECK(e == CL_INVALID_ARG_SIZE &&
              strcmp(why, "clSetKernelArg(put, argument 1) failed with CL_INVALID_ARG_SIZE (-51)") == 0,
          "why: '%s'", why);
    why[0] = '\0';
    e = CL_SET_ARGS_WHY(k, 0, why, sizeof why, CL_ARG(out), CL_ARG(v), CL_ARG(i));
    CHECK(e == CL_SUCCESS && why[0] == '\0', "no words on success: '%s'", why);
    CHECK(set_wrong(k, out, wrong) == EXIT_RUNTIME, "CL_SET_ARGS_GOTO: exit code 3 (EXIT_RUNTIME) on a failure");
    CHECK(set_wrong(k, out, v) == 0, "CL_SET_ARGS_GOTO: 0 on success");

    clReleaseMemObject(out);
    clReleaseKernel(k);
    clReleaseProgram(prog);
    clsession_close(&s);
    return check_summary();
}
