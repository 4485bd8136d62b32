// Damaged and hostile inputs, as a render farm meets them, each through `tyndall render` under a
// 3 GiB address-space limit (ulimit -v) and a 60 s timeout: a VDB cut short at 10, 50 and 90% of
// its length (an interrupted copy), a VDB recording 10 TB of memory, a glTF accessor declaring 4e8
// elements, a PNG declaring 100,000 x 100,000 pixels. Each must end in one clear line naming the
// file and what is wrong, exit code 1, within seconds. A valid VDB whose active region spans 10^12
// voxels (as tiles) renders, within the same limits. Before the strict VDB
// reader, a cut VDB made the renderer allocate without bound (gigabytes within seconds).
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "core/checkpoint.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::CliRun;
namespace fs = std::filesystem;

constexpr uint64_t kLimitKiB = 3ull << 20;  // 3 GiB
constexpr double kSeconds = 15;             // "within seconds", with room for a loaded CI machine

struct Timed {
    CliRun run;
    double seconds = 0;
};

/// `tyndall <args>` under the memory and time limits.
Timed runLimited(const std::string& args) {
    const std::string cmd = "sh -c 'ulimit -v " + std::to_string(kLimitKiB) + " && exec timeout 60 " +
                            std::string(TYNDALL_BINARY) + " " + args + " 2>&1'";
    auto t0 = std::chrono::steady_clock::now();
    Timed t;
    t.run = tyndall::test::runShell(cmd);
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return t;
}

/// `tyndall render <scene>` (tiny, CPU only) under the memory and time limits.
Timed renderLimited(const std::string& scene, const std::string& extra = "") {
    return runLimited("render " + scene + " " + extra + " --size 8x8 --passes 1 --photons 100 --gpu off -o " +
                      tyndall::test::outputDir() + "/hostile.png");
}

std::string folder() {
    std::string dir = tyndall::test::outputDir() + "/hostile";
    fs::create_directories(dir);
    return dir;
}

/// A scene whose global medium reads `vdb` (a path relative to the scene's folder).
std::string vdbScene(const std::string& name, const std::string& vdb) {
    std::string path = folder() + "/" + name + ".json";
    std::ofstream(path) << R"({"name": "hostile",
 "materials": [{"name": "grey", "type": "diffuse", "albedo": 0.5}],
 "media": [{"name": "smoke", "sigma_s": 1, "sigma_a": 0.1, "density": {"file": ")"
                        << vdb << R"("}}], "global_medium": "smoke",
 "shapes": [{"type": "quad", "name": "floor", "material": "grey", "corner": [-50, -20, 50], "edge1": [100, 0, 0], "edge2": [0, 0, -100]}],
 "lights": [{"type": "point", "name": "p", "position": [0, 30, 0], "intensity": [1, 1, 1]}],
 "cameras": [{"name": "c", "position": [0, 10, 120], "target": [0, 10, 0], "up": [0, 1, 0], "fov": 50}]})";
    return path;
}

/// A 64^3 block of noisy density (about 1 MB of leaf data, little of it compressible).
std::string writeNoisyVdb() {
    openvdb::initialize();
    std::string path = folder() + "/noisy.vdb";
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto acc = grid->getAccessor();
    for (int k = 0; k < 64; ++k)
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 64; ++i) acc.setValue(openvdb::Coord(i, j, k), 0.1f + u(rng));
    openvdb::io::File(path).write({grid});
    return path;
}

std::string cutCopy(const std::string& path, double fraction) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string out = folder() + "/cut-" + std::to_string(int(fraction * 100)) + ".vdb";
    std::ofstream(out, std::ios::binary).write(bytes.data(), std::streamsize(size_t(double(bytes.size()) * fraction)));
    return out;
}

TEST(HostileInput, VdbCutShortIsNamedAsTruncatedQuickly) {
    const std::string whole = writeNoisyVdb();
    ASSERT_GT(fs::file_size(whole), 300000u);
    Timed ok = renderLimited(vdbScene("whole", "noisy.vdb"));
    ASSERT_EQ(ok.run.exitCode, 0) << ok.run.output;
    for (double fraction : {0.1, 0.5, 0.9}) {
        const std::string cut = cutCopy(whole, fraction);
        const std::string name = fs::path(cut).filename().string();
        Timed t = renderLimited(vdbScene("cut", name));
        SCOPED_TRACE(name + ": " + t.run.output);
        EXPECT_EQ(t.run.exitCode, 1);
        EXPECT_NE(t.run.output.find("vdb file"), std::string::npos);
        EXPECT_NE(t.run.output.find(name + "': grid 'density': truncated"), std::string::npos);
        EXPECT_NE(t.run.output.find("the file has " + std::to_string(fs::file_size(cut)) + " bytes"),
                  std::string::npos);
        EXPECT_LT(t.seconds, kSeconds);
    }
}

TEST(HostileInput, VdbWithAHugeActiveRegionLoadsSparseWithinBounds) {
    // 3 x 3 x 3 root tiles of 4096^3 voxels, one value: 1.9e12 active voxels that OpenVDB holds in
    // a few hundred bytes. Nothing may densify them: the render goes through, memory bounded.
    openvdb::initialize();
    const std::string path = folder() + "/huge-region.vdb";
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->fill(openvdb::CoordBBox(openvdb::Coord(-4096), openvdb::Coord(2 * 4096 - 1)), 0.001f, true);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.01));
    ASSERT_EQ(grid->activeVoxelCount(), 27ull * 4096 * 4096 * 4096);
    openvdb::io::File(path).write({grid});
    Timed t = renderLimited(vdbScene("huge-region", "huge-region.vdb"));
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 0);
    EXPECT_LT(t.seconds, kSeconds);
}

TEST(HostileInput, VdbWithTwoVoxelsFarApartRendersWithABoundedMajorant) {
    // Two voxels 2^25 - 9 apart on every axis: 2^22 majorant cells of 8 voxels a side, 2^66 in
    // all, which wrapped to 0 in 64 bits and passed for a small grid (found by vdb_fuzz).
    openvdb::initialize();
    const std::string path = folder() + "/far-apart.vdb";
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->tree().setValue(openvdb::Coord(0), 1.0f);
    grid->tree().setValue(openvdb::Coord((1 << 25) - 9), 1.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(1e-4));
    openvdb::io::File(path).write({grid});
    Timed t = renderLimited(vdbScene("far-apart", "far-apart.vdb"));
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 0);
    EXPECT_LT(t.seconds, kSeconds);
}

TEST(HostileInput, VdbDeclaringAHugeMemoryIsRefusedBeforeItIsRead) {
    // A small grid whose recorded memory ("file_mem_bytes", what OpenVDB writes for readers to
    // plan with) says 10 TB: refused from its descriptor, the grid never read.
    openvdb::initialize();
    const std::string path = folder() + "/declares-10tb.vdb";
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 0.5f, true);
    grid->insertMeta("file_mem_bytes", openvdb::Int64Metadata(int64_t(10) << 40));
    openvdb::io::File file(path);
    file.setGridStatsMetadataEnabled(false);
    file.write({grid});
    for (const std::string extra : {"", "--load-memory 4096"}) {
        Timed t = renderLimited(vdbScene("declares-10tb", "declares-10tb.vdb"), extra);
        SCOPED_TRACE(extra + ": " + t.run.output);
        EXPECT_EQ(t.run.exitCode, 1);
        EXPECT_NE(t.run.output.find("declares-10tb.vdb': grid 'density' (the memory it records): needs 10 TiB"),
                  std::string::npos);
        EXPECT_NE(t.run.output.find("--load-memory"), std::string::npos);
        if (!extra.empty()) {
            EXPECT_NE(t.run.output.find("(4096 MiB)"), std::string::npos);
        }
        EXPECT_LT(t.seconds, kSeconds);
    }
}

TEST(HostileInput, VdbWithADegenerateTransformIsRefusedByName) {
    // A grid written with voxels 0.37 wide, then its map's scale changed to 1e-6 in the file (a
    // determinant of 1e-18): OpenVDB reads the map without checking it and cannot make it affine
    // when it is used (ArithmeticError, "nearly singular"). Found by vdb_fuzz; it ended the process.
    openvdb::initialize();
    const std::string path = folder() + "/degenerate.vdb";
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(7)), 0.5f, true);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.37));
    openvdb::io::File(path).write({grid});
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const double written[3] = {0.37, 0.37, 0.37}, tiny[3] = {1e-6, 1e-6, 1e-6};
    const size_t at = bytes.find(std::string(reinterpret_cast<const char*>(written), sizeof written),
                                 bytes.find("UniformScaleMap"));
    ASSERT_NE(at, std::string::npos);
    std::memcpy(&bytes[at], tiny, sizeof tiny);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    Timed t = renderLimited(vdbScene("degenerate", "degenerate.vdb"));
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 1);
    EXPECT_NE(t.run.output.find("degenerate.vdb': grid 'density': index-to-world transform cannot be used"),
              std::string::npos);
    EXPECT_LT(t.seconds, kSeconds);
}

TEST(HostileInput, VdbMetadataOfTheWrongSizeIsRefusedBeforeOpenVdbReadsIt) {
    // The grid's "file_bbox_max" relabelled from vec3i (12 bytes) to vec2i (8): OpenVDB reads 8
    // bytes whatever the record says, falls out of step and takes later bytes for a string's
    // length (1.7 GB resident and 4.5 s for a 17 KB file, found by vdb_fuzz).
    const std::string whole = writeNoisyVdb();
    std::string bytes;
    {
        std::ifstream in(whole, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const size_t at = bytes.find("vec3i", bytes.find("file_bbox_max"));
    ASSERT_NE(at, std::string::npos);
    bytes[at + 3] = '2';
    std::ofstream(folder() + "/relabelled.vdb", std::ios::binary | std::ios::trunc) << bytes;
    Timed t = renderLimited(vdbScene("relabelled", "relabelled.vdb"));
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 1);
    EXPECT_NE(t.run.output.find("relabelled.vdb': grid 'density': metadata 'file_bbox_max': damaged: records 12 "
                                "bytes for a value of type 'vec2i', which has 8"),
              std::string::npos);
    EXPECT_LT(t.seconds, kSeconds);
    rusage children{};
    getrusage(RUSAGE_CHILDREN, &children);  // this process's children: the one render (ctest runs tests apart)
    EXPECT_LT(children.ru_maxrss, 512 << 10) << "KiB resident at most";
}

TEST(HostileInput, GltfAccessorWithAHugeCountIsRefusedByTheBudget) {
    // 4e8 VEC3 positions without a buffer view (zeros, valid glTF): 4.8 GB of floats.
    const std::string path = folder() + "/huge-accessor.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"},
 "accessors": [{"componentType": 5126, "count": 400000000, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}],
 "meshes": [{"name": "big", "primitives": [{"attributes": {"POSITION": 0}}]}],
 "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
    for (const std::string extra : {"", "--load-memory 1024"}) {
        Timed t = renderLimited(path, extra);
        SCOPED_TRACE(extra + ": " + t.run.output);
        EXPECT_EQ(t.run.exitCode, 1);
        EXPECT_NE(t.run.output.find("huge-accessor.gltf"), std::string::npos);
        EXPECT_NE(t.run.output.find("POSITION: accessor 0: 400000000 elements of 3 components: needs"),
                  std::string::npos);
        EXPECT_NE(t.run.output.find("--load-memory"), std::string::npos);
        if (!extra.empty()) {
            EXPECT_NE(t.run.output.find("(1024 MiB)"), std::string::npos);
        }
        EXPECT_LT(t.seconds, kSeconds);
    }
}

uint32_t crc32(const std::string& bytes) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

std::string bigEndian(uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

TEST(HostileInput, TextureDeclaringAHugeSizeIsRefusedFromItsHeader) {
    // A PNG whose header declares 100,000 x 100,000 RGBA pixels (40 GB decoded), its data cut off.
    std::string ihdr = "IHDR" + bigEndian(100000) + bigEndian(100000) + std::string("\x08\x06\x00\x00\x00", 5);
    std::string idat = "IDAT" + std::string(16, '\x55');
    std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + bigEndian(13) + ihdr + bigEndian(crc32(ihdr)) +
                      bigEndian(16) + idat + bigEndian(crc32(idat));
    std::ofstream(folder() + "/huge.png", std::ios::binary) << png;
    const std::string path = folder() + "/huge-texture.json";
    std::ofstream(path) << R"({"name": "huge-texture",
 "materials": [{"name": "wall", "type": "diffuse", "albedo": 0.5, "albedo_texture": "huge.png"}],
 "shapes": [{"type": "quad", "name": "floor", "material": "wall", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
 "lights": [{"type": "point", "name": "p", "position": [0, 1, 0], "intensity": [1, 1, 1]}],
 "cameras": [{"name": "c", "position": [0, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 50}]})";
    Timed t = renderLimited(path);
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 1);
    EXPECT_NE(t.run.output.find("huge.png"), std::string::npos);
    EXPECT_NE(t.run.output.find("a 100000 x 100000 image of 4 channels: needs"), std::string::npos);
    EXPECT_NE(t.run.output.find("--load-memory"), std::string::npos);
    EXPECT_LT(t.seconds, kSeconds);
}

TEST(HostileInput, EnvironmentImageDeclaringAHugeSizeIsRefusedFromItsHeader) {
    // A PNG sky whose header declares 100,000 x 50,000 RGB texels (260 GB to load), its data cut
    // off; given with --environment (the built-in scene) and as a scene's environment file.
    std::string ihdr = "IHDR" + bigEndian(100000) + bigEndian(50000) + std::string("\x08\x02\x00\x00\x00", 5);
    std::string idat = "IDAT" + std::string(16, '\x55');
    std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + bigEndian(13) + ihdr + bigEndian(crc32(ihdr)) +
                      bigEndian(16) + idat + bigEndian(crc32(idat));
    const std::string sky = folder() + "/huge-sky.png";
    std::ofstream(sky, std::ios::binary) << png;
    const std::string scene = folder() + "/huge-sky.json";
    std::ofstream(scene) << R"({"name": "huge-sky",
 "materials": [{"name": "grey", "type": "diffuse", "albedo": 0.5}],
 "shapes": [{"type": "quad", "name": "floor", "material": "grey", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
 "environment": {"file": "huge-sky.png"},
 "cameras": [{"name": "c", "position": [0, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 50}]})";
    for (const std::string args : {"--environment " + sky, scene + " --load-memory 2048"}) {
        Timed t = renderLimited("", args);
        SCOPED_TRACE(args + ": " + t.run.output);
        EXPECT_EQ(t.run.exitCode, 1);
        EXPECT_NE(t.run.output.find("environment image '" + sky +
                                    "': a 100000 x 50000 image of 3 channels (while it loads): needs"),
                  std::string::npos);
        EXPECT_NE(t.run.output.find("raise --load-memory"), std::string::npos);
        EXPECT_LT(t.seconds, kSeconds);
    }
}

/// A real checkpoint of an 8x8 render, then rewritten by `edit` with a valid checksum.
std::string forgedCheckpoint(const std::string& name, const std::function<void(std::string&)>& edit) {
    const std::string path = folder() + "/" + name + ".ckpt";
    CliRun made = tyndall::test::runTyndall("render --size 8x8 --passes 1 --photons 100 --gpu off --quiet -o " +
                                            folder() + "/ckpt.png --checkpoint " + path);
    EXPECT_EQ(made.exitCode, 0) << made.output;
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    bytes.resize(bytes.size() - 8);
    edit(bytes);
    const uint64_t sum = tyndall::checksum64(bytes.data(), bytes.size());
    bytes.append(reinterpret_cast<const char*>(&sum), 8);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    return path;
}

TEST(HostileInput, CheckpointDeclaringAHugeImageIsRefusedBeforeItIsAllocated) {
    // The first layer says 16000 x 16000 (6 GB of sums, over the 3 GiB limit); the file holds
    // 8 x 8. The checksum is valid: only the declared size gives it away.
    const std::string path = forgedCheckpoint("huge-image", [](std::string& b) {
        uint64_t headerSize;
        uint32_t nameSize;
        std::memcpy(&headerSize, &b[8], 8);
        std::memcpy(&nameSize, &b[16 + headerSize + 4], 4);
        ASSERT_EQ(b.substr(16 + headerSize + 8, nameSize), "beauty");
        const int32_t side = 16000;
        std::memcpy(&b[16 + headerSize + 8 + nameSize], &side, 4);
        std::memcpy(&b[16 + headerSize + 12 + nameSize], &side, 4);
    });
    Timed t = runLimited("render --resume " + path + " --quiet");
    SCOPED_TRACE(t.run.output);
    EXPECT_EQ(t.run.exitCode, 1);
    EXPECT_NE(t.run.output.find("checkpoint '" + path + "': malformed checkpoint (a block of 6144000000 bytes"),
              std::string::npos);
    EXPECT_LT(t.seconds, kSeconds);
}

TEST(HostileInput, CheckpointLargerThanTheLoadingBudgetIsRefusedBeforeItIsRead) {
    // 40 GiB (sparse): the default budget under a 3 GiB limit is 2.25 GiB.
    const std::string path = folder() + "/huge-file.ckpt";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << "TYNCKPT\x01";
    fs::resize_file(path, uint64_t(40) << 30);
    for (const std::string extra : {"", "--load-memory 1024"}) {
        Timed t = runLimited("render --resume " + path + " --quiet " + extra);
        SCOPED_TRACE(extra + ": " + t.run.output);
        EXPECT_EQ(t.run.exitCode, 1);
        EXPECT_NE(t.run.output.find("checkpoint '" + path + "' (40960 MiB, read and parsed): needs 81920 MiB"),
                  std::string::npos);
        EXPECT_NE(t.run.output.find(extra.empty() ? "raise --load-memory" : "(1024 MiB)"), std::string::npos);
        EXPECT_LT(t.seconds, kSeconds);
    }
    fs::remove(path);
}

}  // namespace
