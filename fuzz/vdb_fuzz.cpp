// libFuzzer target for the VDB path (loading/vdb_file.h, then VdbDensityGrid): any bytes, as a
// .vdb file, must either load within a 256 MiB loading budget or throw tyndall::Error. A crash,
// another exception, an AddressSanitizer report, an input running past the per-input timeout or
// the memory limit is a bug. Seeds: small real grids written by make_vdb_seeds at build time,
// whole, cut and with bytes flipped. Leak detection is off for this target (run_fuzz.cmake):
// OpenVDB leaks the node under construction when a read throws, which is not ours to fix.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/load_budget.h"
#include "loading/vdb_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The reader works on files (it checks descriptors against the file's length): an in-memory
    // one, reached through its /proc path, so nothing is left on disk however the run ends.
    static const int fd = memfd_create("tyndall-vdb-fuzz", 0);
    static const std::string path = "/proc/self/fd/" + std::to_string(fd);
    if (fd < 0 || ftruncate(fd, 0) != 0) return 0;
    for (size_t done = 0; done < size;) {
        const ssize_t n = pwrite(fd, data + done, size - done, off_t(done));
        if (n <= 0) return 0;
        done += size_t(n);
    }
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
