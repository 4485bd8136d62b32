// libFuzzer target for the checkpoint reader: any bytes must either parse (and, as a render
// checkpoint, give a record) or throw tyndall::Error; a crash, another exception, a leak, an
// AddressSanitizer report or an allocation larger than the input allows is a bug. Inputs whose last
// byte is odd get their checksum appended, so that the fuzzer reaches the parser behind the
// checksum (a damaged file with a valid checksum: what a hostile file is). Built and run by ctest
// through fuzz/run_fuzz.cmake; see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/render_checkpoint.h"
#include "core/checkpoint.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (!bytes.empty() && (bytes.back() & 1)) {
        const uint64_t sum = tyndall::checksum64(bytes.data(), bytes.size());
        bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
    }
    try {
        tyndall::Checkpoint c = tyndall::parseCheckpoint(bytes, "fuzz-input");
        tyndall::app::readRecord(c, "fuzz-input");
    } catch (const tyndall::Error&) {
        // The expected outcome for bad input.
    }
    return 0;
}
