#pragma once
// Checkpoint files: a render's whole state between passes, so a killed render can go on where it
// stopped and end with the same bits as one never interrupted (passes are pure functions of their
// index: the state is the accumulators' double sums plus what the next pass needs, kept in a JSON
// header by the caller: resolved settings, scene file and hash, pass count, elapsed time).
//
// Layout (little-endian): magic "TYNCKPT\x01"; u64 header length; header JSON; u32 layer count;
// per layer: u32 name length, name, i32 width, i32 height, u64 passes, u64 rejected samples,
// 3 x width x height f64 sums; then a u64 checksum of every byte before it (FNV-1a over 64-bit
// words, the tail byte-wise). A file that is cut short
// or altered fails the checksum; a file of another kind fails the magic.
//
// Writing is atomic (write a temporary file beside the target, fsync it, rename it over the
// target, fsync the directory): a process killed at any instant leaves the old checkpoint or the
// new one, never a torn one. At most one stale "<file>.tmp" is left behind, and the next write
// replaces it.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/accumulator.h"

namespace tyndall {

class LoadBudget;

struct Checkpoint {
    nlohmann::json header = nlohmann::json::object();
    std::vector<std::pair<std::string, Accumulator>> layers;  ///< named, e.g. "beauty" first

    /// The layer called `name`; throws Error naming the file when absent.
    const Accumulator& layer(const std::string& name, const std::string& file) const;
};

/// The file's bytes; parseCheckpoint(serializeCheckpoint(c)) == c.
std::string serializeCheckpoint(const Checkpoint& checkpoint);
/// Throws Error "<file>: ..." for a foreign file (magic), a truncated or altered one (checksum)
/// and a malformed one (sizes, JSON). Every declared size (header, names, layers) is checked
/// against the bytes left before anything of that size is allocated.
Checkpoint parseCheckpoint(const std::string& bytes, const std::string& file);

/// Writes `bytes` to `path` atomically (see above); `midWrite`, when given, runs after the first
/// half is written to the temporary file (tests stall there to be killed mid-write). Throws Error
/// naming the file when it cannot be written; the old file is then untouched.
void writeFileAtomically(const std::string& path, const std::string& bytes, const std::function<void()>& midWrite = {});
void saveCheckpoint(const std::string& path, const Checkpoint& checkpoint, const std::function<void()>& midWrite = {});
/// Reads and parses; Error "checkpoint '<path>': ..." when missing or bad. With a budget, the
/// file's length is checked before it is read: reading holds the file's bytes and the layers they
/// become (twice its length), refused as LoadBudget::check refuses.
Checkpoint loadCheckpoint(const std::string& path, const LoadBudget* budget = nullptr);

/// 64-bit FNV-1a, continued from `hash` (the scene hash uses it).
uint64_t fnv1a(const void* data, size_t size, uint64_t hash = 0xcbf29ce484222325ull);
/// The file checksum: FNV-1a's step over 8-byte words (8x fewer dependent multiplies; checkpoints
/// run to hundreds of MB), the remaining bytes one by one.
uint64_t checksum64(const void* data, size_t size);

}  // namespace tyndall
