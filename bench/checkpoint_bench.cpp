// Checkpoint cost at 1920x1080 (Google Benchmark): what `tyndall render --checkpoint` pays each
// time it saves, against the baseline of writing the same image once as an EXR (what every
// render pays at its end), in the same run. Not run by ctest.
//
//   cmake --build build --target checkpoint_bench && build/bench/checkpoint_bench --benchmark_repetitions=3
// Files go to $TMPDIR (default /tmp); the reported "bytes" counter is the checkpoint's size.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/checkpoint.h"
#include "core/image_io.h"
#include "core/layer_accumulator.h"
#include "core/rng.h"

namespace tyndall {
namespace {

constexpr int kW = 1920, kH = 1080;

std::string tmpPath(const std::string& name) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/" + name;
}

Image noisyImage(uint64_t seed) {
    Image img(kW, kH);
    Rng rng = Rng::forKey(seed, 0, 0, StreamPurpose::Test);
    for (Rgb& p : img.pixels) p = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
    return img;
}

/// A render's state after a few passes: the beauty sums only, or with --aov's four more layers.
LayerAccumulator state(bool aov) {
    LayerAccumulator acc(kW, kH, aov);
    for (uint64_t i = 0; i < 2; ++i) {
        Image a = noisyImage(i);
        if (aov)
            acc.addPass(a, a, a, a);
        else
            acc.addPass(a);
    }
    return acc;
}

void BM_CheckpointSave1080p(benchmark::State& st) {
    const bool aov = st.range(0) != 0;
    Checkpoint c;
    c.header = {{"format", "bench"}};
    c.layers = state(aov).named();
    const std::string path = tmpPath("tyndall_bench.ckpt");
    size_t bytes = 0;
    for (auto _ : st) {
        std::string data = serializeCheckpoint(c);
        bytes = data.size();
        writeFileAtomically(path, data);  // write beside, fsync, rename, fsync the directory
    }
    st.counters["bytes"] = double(bytes);
    st.SetBytesProcessed(int64_t(st.iterations()) * int64_t(bytes));
    std::filesystem::remove(path);
}
BENCHMARK(BM_CheckpointSave1080p)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CheckpointSerializeOnly1080p(benchmark::State& st) {
    Checkpoint c;
    c.layers = state(false).named();
    for (auto _ : st) benchmark::DoNotOptimize(serializeCheckpoint(c));
}
BENCHMARK(BM_CheckpointSerializeOnly1080p)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Baseline: the final image itself, a float RGB EXR (zip) of the same size.
void BM_ExrWrite1080p(benchmark::State& st) {
    Image img = state(false).beauty().mean();
    const std::string path = tmpPath("tyndall_bench.exr");
    for (auto _ : st) writeImage(path, img);
    st.counters["bytes"] = double(std::filesystem::file_size(path));
    std::filesystem::remove(path);
}
BENCHMARK(BM_ExrWrite1080p)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace tyndall

BENCHMARK_MAIN();
