// libFuzzer target for the VDB path (loading/vdb_file.h, then VdbDensityGrid): any bytes, as a
// .vdb file, must either load within a 256 MiB loading budget or throw tyndall::Error. A crash,
// another exception, an AddressSanitizer report, an input running past the per-input timeout or
// the memory limit is a bug. Seeds: small real grids written by make_vdb_seeds at build time,
// whole, cut and with bytes flipped. Leak detection is off for this target (run_fuzz.cmake):
// OpenVDB leaks the node under construction when a read throws, which is not ours to fix.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/load_budget.h"
#include "loading/vdb_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The reader works on files (it checks descriptors against the file's length).
    static const std::string path = "/tmp/tyndall-vdb-fuzz-" + std::to_string(getpid()) + ".vdb";
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    tyndall::LoadBudget budget(uint64_t(256) << 20);
    tyndall::VdbGridSource source;
    source.file = path;
    try {
        auto grid = tyndall::VdbDensityGrid::load(source, [](const std::string&) {}, &budget);
        grid->density(tyndall::Vec3(0.5f, 0.5f, 0.5f));
    } catch (const tyndall::Error&) {
        // The expected outcome for bad input.
    }
    return 0;
}
