// OpenVDB's compressed-block readers as Tyndall links them (loading/vdb_stream.h): a block whose
// stored size does not fit its destination or the bytes left is refused before anything is
// written or allocated, and valid blocks (written by OpenVDB's own writers) read back exactly.
// OpenVDB 10's own readers copy a block stored uncompressed with a size larger than its
// destination straight into it: the guard bytes past the destination catch that.
#include <gtest/gtest.h>
#include <openvdb/io/Compression.h>

#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "loading/vdb_stream.h"

namespace {

using Reader = void (*)(std::istream&, char*, size_t);

struct Case {
    const char* codec;
    Reader read;
};
const Case kCases[] = {{"blosc", &openvdb::io::bloscFromStream}, {"zip", &openvdb::io::unzipFromStream}};

/// Reads `bytes` as one block into a 64-byte destination followed by 4096 guard bytes; returns
/// the error, "" when it read.
std::string readBlock(Reader read, std::string bytes, std::vector<char>& dest) {
    dest.assign(64 + 4096, '\x5a');
    tyndall::VdbMemoryBuffer buffer(bytes.data(), bytes.size());
    std::istream stream(&buffer);
    stream.exceptions(std::ios::failbit | std::ios::badbit);
    try {
        read(stream, dest.data(), 64);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

std::string sized(int64_t size, const std::string& payload) {
    return std::string(reinterpret_cast<const char*>(&size), 8) + payload;
}

bool guardIntact(const std::vector<char>& dest) {
    for (size_t i = 64; i < dest.size(); ++i)
        if (dest[i] != '\x5a') return false;
    return true;
}

TEST(VdbBlocks, StoredUncompressedLargerThanTheDestinationIsRefusedUnwritten) {
    for (const Case& c : kCases) {
        SCOPED_TRACE(c.codec);
        std::vector<char> dest;
        const std::string error = readBlock(c.read, sized(-4096, std::string(4096, '\x01')), dest);
        EXPECT_NE(error.find("stored uncompressed as 4096 bytes, where 64 belong"), std::string::npos) << error;
        EXPECT_TRUE(guardIntact(dest));
        EXPECT_EQ(dest[0], '\x5a') << "nothing is read before the size is checked";
        EXPECT_NE(readBlock(c.read, sized(INT64_MIN, ""), dest), "");
        EXPECT_TRUE(guardIntact(dest));
    }
}

TEST(VdbBlocks, SizesLargerThanTheBytesLeftAreRefusedBeforeAllocating) {
    for (const Case& c : kCases) {
        SCOPED_TRACE(c.codec);
        std::vector<char> dest;
        // 2^62 bytes could never be allocated: the refusal must come from the check, not from new.
        const std::string error = readBlock(c.read, sized(int64_t(1) << 62, std::string(100, '\x01')), dest);
        EXPECT_NE(error.find("4611686018427387904 bytes recorded, 100 left in the grid"), std::string::npos) << error;
        EXPECT_TRUE(guardIntact(dest));
    }
}

TEST(VdbBlocks, ValidBlocksReadBackExactlyAndLyingHeadersAreRefused) {
    std::vector<float> values(16);
    for (size_t i = 0; i < values.size(); ++i) values[i] = 0.25f * float(i % 5);
    const char* data = reinterpret_cast<const char*>(values.data());
    std::ostringstream blosc, zip;
    openvdb::io::bloscToStream(blosc, data, sizeof(float), values.size());
    openvdb::io::zipToStream(zip, data, 64);
    for (auto [c, bytes] : {std::pair{kCases[0], blosc.str()}, std::pair{kCases[1], zip.str()}}) {
        SCOPED_TRACE(c.codec);
        int64_t stored = 0;
        std::memcpy(&stored, bytes.data(), 8);
        ASSERT_GT(stored, 0) << "the writer compressed the block";
        std::vector<char> dest;
        EXPECT_EQ(readBlock(c.read, bytes, dest), "");
        EXPECT_EQ(std::memcmp(dest.data(), data, 64), 0);
        EXPECT_TRUE(guardIntact(dest));
        // The same block read into a 64-byte destination, but its own header says otherwise.
        std::string lying = bytes;
        if (std::string(c.codec) == "blosc") {
            const uint32_t nbytes = 4096;  // blosc's header: uncompressed size at byte 4
            std::memcpy(&lying[8 + 4], &nbytes, 4);
        } else {
            lying.back() ^= 0x55;  // zlib's Adler-32 checksum
        }
        EXPECT_NE(readBlock(c.read, lying, dest), "");
        EXPECT_TRUE(guardIntact(dest));
    }
}

}  // namespace
