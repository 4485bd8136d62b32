#pragma once
// The loading memory budget (`--load-memory MiB`, default 16384): what loading one scene may
// allocate for its grids, buffers, accessors and textures, all together. Loaders ask before they
// allocate, with the size the file declares (a VDB grid's recorded memory and voxel count, a glTF
// accessor's count x element size, an image header's width x height x channels), so that a
// hostile or damaged file is refused with one line instead of exhausting the machine. It bounds
// loading only; `--memory` bounds the render's working memory.
//
// One budget per scene load (loadSceneData makes it; a view file's base scene shares its view
// file's). reserve() and check() are safe from several threads.
#include <atomic>
#include <cstdint>
#include <string>

namespace tyndall {

class LoadBudget {
public:
    static constexpr uint64_t kDefaultMiB = 16384;

    explicit LoadBudget(uint64_t limitBytes = kDefaultMiB << 20) : m_limit(limitBytes) {}

    /// Counts `bytes` as held by the scene from now on. Throws Error when they do not fit what is
    /// left: "<what>: needs N MiB, more than the loading memory budget allows (L MiB, U MiB of it
    /// taken by the scene so far); raise --load-memory (MiB) if the file is trusted". `what` names
    /// the file and the grid, accessor or texture.
    void reserve(uint64_t bytes, const std::string& what);
    /// The same test for memory held only while loading (a decoded image before it is mip-mapped
    /// to disk): nothing is counted.
    void check(uint64_t bytes, const std::string& what) const;

    uint64_t limitBytes() const { return m_limit; }
    uint64_t usedBytes() const { return m_used.load(); }

private:
    uint64_t m_limit;
    std::atomic<uint64_t> m_used{0};
};

/// The budget when none is given: kDefaultMiB, or three quarters of the machine's physical memory
/// or of the process's address-space limit (ulimit -v) when that is less, so that a refusal
/// comes before the machine runs out.
uint64_t defaultLoadMemoryBytes();

/// "1.5 MiB", "20480 MiB", "3.64 TiB": one decimal below 10 MiB, TiB from a million MiB.
std::string describeBytes(uint64_t bytes);

}  // namespace tyndall
