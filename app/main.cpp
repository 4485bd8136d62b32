// tyndall: the command-line front end. Library code throws tyndall::Error; this is the only place
// that turns errors into a one-line message and a non-zero exit.
#include <CLI/CLI.hpp>
#include <malloc.h>

#include <cstdio>
#include <exception>
#include <new>

#include "app/cmd_bench.h"
#include "app/cmd_compare.h"
#include "app/cmd_reference.h"
#include "app/cmd_render.h"
#include "app/cmd_view.h"
#include "core/error.h"

namespace {
// A pass frees and allocates again blocks of a few MB to ~30 MB (pass images, photon batches,
// BVH and grid arrays). glibc's dynamic mmap threshold makes whether they come from the heap or
// from fresh mmaps (page-faulted anew every pass) depend on what was freed earlier: pooling the
// largest buffers (camera_tracer.h) lowered it and tripled a 512x512 pass's page faults
// (CHANGELOG.md, 2026-12-02). Fixed here instead: blocks up to glibc's 32 MiB maximum come from the
// heap, and freed heap memory up to 256 MiB stays mapped for the next pass (the peak is what the
// memory plan bounds; this only keeps it instead of returning and faulting it in again).
void setAllocatorForPasses() {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
}
}  // namespace

int main(int argc, char** argv) {
    setAllocatorForPasses();
    CLI::App app{"Tyndall: progressive photon beams for fog, smoke, water and glass", "tyndall"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Help for every command");
    int exitCode = 0;
    tyndall::app::addRenderCommand(app, exitCode);
    tyndall::app::addBenchCommand(app, exitCode);
    tyndall::app::addCompareCommand(app, exitCode);
    tyndall::app::addReferenceCommand(app, exitCode);
    tyndall::app::addViewCommand(app, exitCode);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "tyndall: %s (see tyndall --help)\n", e.what());
        return 2;
    } catch (const tyndall::Error& e) {
        std::fprintf(stderr, "tyndall: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc& e) {
        std::fprintf(stderr,
                     "tyndall: out of memory (%s) outside the render loop's tracked allocations (scene loading, "
                     "image output): lower --size or the scene's size, or raise the memory limit\n",
                     e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tyndall: unexpected error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
