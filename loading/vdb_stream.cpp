#include "loading/vdb_stream.h"

#include <blosc.h>
#include <openvdb/io/Compression.h>
#include <zlib.h>

#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tyndall {

VdbMemoryBuffer::VdbMemoryBuffer(char* data, size_t size) {
    setg(data, data, data + size);
}

VdbMemoryBuffer::pos_type VdbMemoryBuffer::seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) {
    char* base = dir == std::ios_base::beg ? eback() : dir == std::ios_base::cur ? gptr() : egptr();
    return seekTo(base - eback() + off);
}

VdbMemoryBuffer::pos_type VdbMemoryBuffer::seekpos(pos_type pos, std::ios_base::openmode) {
    return seekTo(off_type(pos));
}

VdbMemoryBuffer::pos_type VdbMemoryBuffer::seekTo(off_type p) {
    if (p < 0 || p > egptr() - eback()) return pos_type(off_type(-1));
    setg(eback(), eback() + p, egptr());
    return pos_type(p);
}

namespace {

[[noreturn]] void damaged(const char* codec, const std::string& what) {
    throw std::runtime_error(std::string("a damaged ") + codec + " block: " + what);
}

/// The block's stored size (negative: stored uncompressed), checked against the destination's
/// size and the bytes left in the stream before anything is read or allocated.
int64_t blockSize(std::istream& is, size_t numBytes, const char* codec) {
    int64_t size = 0;
    is.read(reinterpret_cast<char*>(&size), sizeof size);
    if (!is.good()) damaged(codec, "its size is cut off");
    const uint64_t stored = size <= 0 ? 0 - uint64_t(size) : uint64_t(size);  // no overflow at INT64_MIN
    if (size <= 0 && stored != numBytes)
        damaged(codec, "stored uncompressed as " + std::to_string(stored) + " bytes, where " + std::to_string(numBytes) +
                           " belong");
    if (const auto* buffer = dynamic_cast<const VdbMemoryBuffer*>(is.rdbuf()); buffer && stored > buffer->left())
        damaged(codec, std::to_string(stored) + " bytes recorded, " + std::to_string(buffer->left()) + " left in the grid");
    return size;
}

/// Reads a block's size and, where nothing is left to decompress, the block itself: one stored
/// uncompressed is read (or skipped: data == nullptr), a compressed one skipped when data is null.
/// Otherwise returns the compressed bytes, for the caller to decompress into `data`.
std::optional<std::vector<char>> compressedBlock(std::istream& is, char* data, size_t numBytes, const char* codec) {
    const int64_t size = blockSize(is, numBytes, codec);
    if (size <= 0) {
        if (data)
            is.read(data, std::streamsize(numBytes));
        else
            is.seekg(std::streamoff(numBytes), std::ios_base::cur);
        return std::nullopt;
    }
    if (!data) {
        is.seekg(std::streamoff(size), std::ios_base::cur);
        return std::nullopt;
    }
    std::vector<char> bytes(static_cast<size_t>(size));
    is.read(bytes.data(), std::streamsize(size));
    return bytes;
}

}  // namespace

}  // namespace tyndall

namespace openvdb {
OPENVDB_USE_VERSION_NAMESPACE
namespace OPENVDB_VERSION_NAME {
namespace io {

void bloscFromStream(std::istream& is, char* data, size_t numBytes) {
    const std::optional<std::vector<char>> block = tyndall::compressedBlock(is, data, numBytes, "blosc");
    if (!block) return;
    const std::vector<char>& src = *block;
    size_t declared = 0;
    if (src.size() < BLOSC_MIN_HEADER_LENGTH || blosc_cbuffer_validate(src.data(), src.size(), &declared) != 0)
        tyndall::damaged("blosc", "its header does not fit its " + std::to_string(src.size()) + " bytes");
    if (declared != numBytes)
        tyndall::damaged("blosc", "it holds " + std::to_string(declared) + " bytes, where " + std::to_string(numBytes) +
                                      " belong");
    const int got = blosc_decompress_ctx(src.data(), data, numBytes, 1);
    if (got < 0 || size_t(got) != numBytes) tyndall::damaged("blosc", "it does not decompress");
}

void unzipFromStream(std::istream& is, char* data, size_t numBytes) {
    const std::optional<std::vector<char>> block = tyndall::compressedBlock(is, data, numBytes, "zip");
    if (!block) return;
    const std::vector<char>& src = *block;
    uLongf got = uLongf(numBytes);
    if (uncompress(reinterpret_cast<Bytef*>(data), &got, reinterpret_cast<const Bytef*>(src.data()), uLong(src.size())) !=
            Z_OK ||
        got != numBytes)
        tyndall::damaged("zip", "it does not decompress to " + std::to_string(numBytes) + " bytes");
}

}  // namespace io
}  // namespace OPENVDB_VERSION_NAME
}  // namespace openvdb
