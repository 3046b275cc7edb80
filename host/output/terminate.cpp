/* terminate.cpp - a C++ exception that nobody catches (in the OpenCL driver's compiler, in
 * OpenCV) ends the run with one line and exit 3, its unfinished outputs removed, instead of
 * abort() (exit 134). The usual one is std::bad_alloc in LLVM under a memory limit (ulimit -v):
 * the line says so. outdir_install_signal_handlers installs it (main.c, before any command). */
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include <unistd.h>

extern "C" {
#include "outdir.h"
}

namespace {

void say(const char *text)
{
    ssize_t w = write(2, text, strlen(text));
    (void)w;
}

[[noreturn]] void on_terminate()
{
    const char *what = "an unknown exception";
    bool oom = false;
    try {
        std::exception_ptr e = std::current_exception();
        if (e)
            std::rethrow_exception(e);
        what = "no exception (std::terminate was called)";
    } catch (const std::bad_alloc &) {
        oom = true;
    } catch (const std::exception &ex) {
        what = ex.what();
    } catch (...) {
    }
    if (oom) {
        say("brdfbench: out of memory in a library (std::bad_alloc, most likely the OpenCL driver's compiler; is the "
            "address space limited, ulimit -v?); the run is stopped and its unfinished outputs removed\n");
    } else {
        say("brdfbench: a library ended with an uncaught C++ exception (");
        say(what);
        say("); the run is stopped and its unfinished outputs removed\n");
    }
    outdir_remove_own();
    _exit(3);
}

}  // namespace

extern "C" void outdir_install_terminate_handler(void) { std::set_terminate(on_terminate); }
