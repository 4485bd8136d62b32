// Writes the VDB fuzzer's seed corpus into the folder given: small real grids as OpenVDB writes
// them (a constant block, noise, scattered voxels, tiles, half floats, two grids, a level set, a
// vector grid), each also cut at 10, 50 and 90% of its length and with single bytes flipped at
// fixed places. Run by run_fuzz.cmake before vdb_fuzz; each file stays under the fuzzer's
// -max_len.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace {

openvdb::FloatGrid::Ptr fog(const std::string& name) {
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName(name);
    g->setGridClass(openvdb::GRID_FOG_VOLUME);
    return g;
}

void variants(const std::string& dir, const std::string& name, const openvdb::GridPtrVec& grids) {
    const std::string path = dir + "/" + name + ".vdb";
    openvdb::io::File(path).write(grids);
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (int percent : {10, 50, 90})
        std::ofstream(dir + "/" + name + "-cut" + std::to_string(percent) + ".vdb", std::ios::binary)
            .write(bytes.data(), std::streamsize(bytes.size() * size_t(percent) / 100));
    for (int k = 1; k <= 3; ++k) {
        std::string flipped = bytes;
        flipped[flipped.size() * size_t(k) / 4] ^= char(0x5a);
        std::ofstream(dir + "/" + name + "-flip" + std::to_string(k) + ".vdb", std::ios::binary) << flipped;
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    const std::string dir = argv[1];
    openvdb::initialize();
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.05f, 1.0f);

    auto block = fog("density");
    block->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(7)), 0.5f, true);
    variants(dir, "block", {block});

    auto noise = fog("density");
    auto acc = noise->getAccessor();
    for (int k = 0; k < 12; ++k)
        for (int j = 0; j < 12; ++j)
            for (int i = 0; i < 12; ++i) acc.setValue(openvdb::Coord(i, j, k), u(rng));
    variants(dir, "noise", {noise});

    auto scattered = fog("density");
    std::uniform_int_distribution<int> c(-300, 300);
    auto sacc = scattered->getAccessor();
    for (int n = 0; n < 60; ++n) sacc.setValue(openvdb::Coord(c(rng), c(rng), c(rng)), u(rng));
    variants(dir, "scattered", {scattered});

    auto tiles = fog("density");
    tiles->fill(openvdb::CoordBBox(openvdb::Coord(-4096), openvdb::Coord(4095)), 0.01f, true);
    variants(dir, "tiles", {tiles});

    auto half = noise->deepCopy();
    half->setSaveFloatAsHalf(true);
    variants(dir, "half", {half});

    auto temperature = fog("temperature");
    temperature->fill(openvdb::CoordBBox(openvdb::Coord(2), openvdb::Coord(5)), 3.0f, true);
    variants(dir, "two-grids", {block, temperature});

    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(4.0f, openvdb::Vec3f(0), 1.0f);
    sphere->setName("density");
    variants(dir, "level-set", {sphere});

    auto vec = openvdb::Vec3SGrid::create();
    vec->setName("velocity");
    vec->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(3)), openvdb::Vec3s(1, 0, 0), true);
    variants(dir, "vector", {vec});
    return 0;
}
