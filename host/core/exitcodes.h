/* exitcodes.h - the process exit codes every command uses (docs/architecture.md, habit 4). */
#ifndef BRDF_EXITCODES_H
#define BRDF_EXITCODES_H

enum brdf_exit {
    EXIT_OK = 0,          /* success                                              */
    EXIT_GATE_FAIL = 1,   /* an accuracy gate failed                              */
    EXIT_USAGE = 2,       /* bad command line or input file                       */
    EXIT_RUNTIME = 3,     /* OpenCL, I/O or other runtime error                   */
    EXIT_NO_DEVICE = 77   /* no OpenCL platform or device (ctest's skip code)     */
};

#endif
