#include "loading/vdb_grid.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <regex>
#include <sstream>

#include "core/checkpoint.h"
#include "core/error.h"
#include "core/load_budget.h"
#include "loading/vdb_file.h"
#include "loading/vdb_grid_openvdb.h"

namespace tyndall {

namespace {
using FloatTree = openvdb::FloatTree;
// Unregistered ("unsafe") accessor: the tree is never modified after construction, so skipping
// OpenVDB's accessor registry (a concurrent hash map) is safe and much cheaper.
using Accessor = openvdb::tree::ValueAccessor<const FloatTree, false>;

std::atomic<uint64_t> g_nextGridId{1};

/// Floor division for possibly negative integers.
int64_t floorDiv(int64_t a, int64_t b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

Affine3 affineFromOpenVdb(const openvdb::math::Mat4d& m) {
    // OpenVDB multiplies row vectors (p' = p M, translation in row 3); Affine3 acts on columns.
    Affine3 a;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) a.m[i][j] = float(m(j, i));
        a.m[i][3] = float(m(3, i));
    }
    return a;
}

openvdb::math::Mat4d affineToOpenVdb(const Affine3& a) {
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m(j, i) = a.m[i][j];
        m(3, i) = a.m[i][3];
    }
    return m;
}
}  // namespace

struct VdbDensityGrid::Impl {
    openvdb::FloatGrid::ConstPtr grid;
    uint64_t id = 0;
    std::string label;
    std::string name;
    float scale = 1.0f;
    float background = 0;  // taken out of the values (VdbGridSource::ambientBackground)
    Affine3 indexToWorld, worldToIndex;
    bool empty = true;
    openvdb::CoordBBox positiveBox;  // index bounds of the voxels holding a value > 0
    Bounds3 worldBounds;
    MajorantGrid majorants;
    float maxDensity = 0;
    float meanDensity = 0;
    double integratedDensity = 0;  // sum of the positive values x voxel volume x scale
    uint64_t activeVoxels = 0;
    int majorantBlock = 0;
    bool hasDense = false;
    DensityVolume dense;  // the denseVolume() lattice when it fits kMaxDenseVoxels: density() reads it
};

namespace {
// Per-thread accessors, a few grids deep (a scene rarely has more than one or two grid media).
struct AccessorCache {
    static constexpr int kSlots = 4;
    uint64_t ids[kSlots] = {0, 0, 0, 0};
    std::optional<Accessor> accessors[kSlots];
    int next = 0;
};
thread_local AccessorCache t_accessors;

Accessor& accessorFor(const VdbDensityGrid::Impl& g) {
    AccessorCache& c = t_accessors;
    for (int i = 0; i < AccessorCache::kSlots; ++i)
        if (c.ids[i] == g.id) return *c.accessors[i];
    int i = c.next;
    c.next = (c.next + 1) % AccessorCache::kSlots;
    c.ids[i] = g.id;
    c.accessors[i].emplace(g.grid->tree());
    return *c.accessors[i];
}
}  // namespace

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::shared_ptr<const VdbDensityGrid> makeVdbDensityGrid(openvdb::FloatGrid::ConstPtr grid,
                                                         const Affine3& sceneTransform, float scale,
                                                         const std::string& label, int majorantBlock,
                                                         LoadBudget* budget, float background) {
    auto fail = [&](const std::string& what) { throw Error(label + ": " + what); };
    if (!(scale >= 0) || !std::isfinite(scale)) fail("density scale must be a finite number >= 0");
    if (!grid->transform().isLinear())
        fail("has a non-linear (frustum) transform; only affine index-to-world transforms are supported");
    if (grid->background() > 0.0f)
        fail("background value is " + std::to_string(grid->background()) +
             " > 0; a density grid must be 0 outside its voxels (a fog volume)");
    if (majorantBlock < 1) fail("majorant block size must be >= 1");

    auto impl = std::make_unique<VdbDensityGrid::Impl>();
    impl->id = g_nextGridId.fetch_add(1);
    impl->label = label;
    impl->name = grid->getName();
    impl->scale = scale;
    impl->background = background;
    try {
        impl->indexToWorld = sceneTransform * affineFromOpenVdb(grid->transform().baseMap()->getAffineMap()->getMat4());
    } catch (const openvdb::Exception& e) {  // a map OpenVDB cannot make affine: a (nearly) singular one
        fail("index-to-world transform cannot be used (" + std::string(e.what()) + ")");
    }
    float det = impl->indexToWorld.determinant();
    if (!(std::abs(det) > 0) || !std::isfinite(det))
        fail("index-to-world transform (with the scene transform) is singular");
    impl->worldToIndex = impl->indexToWorld.inverse();

    // One sweep over every stored value (active or not: trilinear sampling reads both).
    bool negative = grid->background() < 0.0f;
    double activeSum = 0, positiveSum = 0;
    float maxValue = 0;
    openvdb::CoordBBox box;
    for (auto it = grid->tree().cbeginValueAll(); it; ++it) {
        float v = *it;
        if (it.isValueOn()) {
            uint64_t n = it.getVoxelCount();
            impl->activeVoxels += n;
            activeSum += double(std::max(v, 0.0f)) * double(n);
        }
        if (v < 0) negative = true;
        if (!(v > 0)) continue;
        positiveSum += double(v) * double(it.getVoxelCount());
        openvdb::CoordBBox b;
        it.getBoundingBox(b);
        box.expand(b);
        maxValue = std::max(maxValue, v);
    }
    if (!std::isfinite(maxValue) || !std::isfinite(activeSum)) fail("holds non-finite values");
    if (negative) {
        // Negative density means nothing physical: clamp so that every consumer sees the same field.
        openvdb::FloatGrid::Ptr copy = grid->deepCopy();
        for (auto it = copy->tree().beginValueAll(); it; ++it)
            if (*it < 0) it.setValue(0.0f);
        openvdb::tools::changeBackground(copy->tree(), 0.0f);
        grid = copy;
    }
    impl->grid = grid;
    impl->maxDensity = maxValue * scale;
    impl->meanDensity = impl->activeVoxels > 0 ? float(activeSum / double(impl->activeVoxels)) * scale : 0.0f;
    // Each voxel's trilinear hat integrates to one index-space voxel.
    impl->integratedDensity = positiveSum * double(scale) * std::abs(double(det));
    impl->empty = box.empty();
    if (impl->empty) return std::make_shared<const VdbDensityGrid>(std::move(impl));
    impl->positiveBox = box;

    // Trilinear support: one voxel beyond the positive voxels on every side.
    const openvdb::Coord lo = box.min(), hi = box.max();
    Bounds3 support;
    support.lo = Vec3(float(lo.x() - 1), float(lo.y() - 1), float(lo.z() - 1));
    support.hi = Vec3(float(hi.x() + 1), float(hi.y() + 1), float(hi.z() + 1));
    impl->worldBounds = transformBounds(impl->indexToWorld, support);

    // Majorant cells: cell c covers index [O + cB, O + (c+1)B] with O = lo - 1. A point there
    // interpolates voxels O + cB .. O + (c+1)B + 1; one more voxel each side absorbs rounding.
    // Sparse grids spanning a huge index range get coarser cells (a bounded majorant grid).
    int64_t B = majorantBlock;
    int64_t origin[3], res[3];
    while (true) {
        for (int a = 0; a < 3; ++a) {
            origin[a] = int64_t(lo[a]) - 1;
            res[a] = std::max<int64_t>(1, (int64_t(hi[a]) - int64_t(lo[a]) + 2 + B - 1) / B);
        }
        // Each side alone can exceed 2^32 cells (int32 coordinates): no product before it fits.
        const int64_t most = VdbDensityGrid::kMaxMajorantCells;
        if (res[0] <= most && res[1] <= most / res[0] && res[2] <= most / (res[0] * res[1])) break;
        B *= 2;
    }
    impl->majorantBlock = int(B);
    Affine3 indexToCell = Affine3::scaleTranslate(
        Vec3(1.0f / float(B)),
        Vec3(-float(origin[0]) / float(B), -float(origin[1]) / float(B), -float(origin[2]) / float(B)));
    MajorantGrid maj(indexToCell * impl->worldToIndex, int(res[0]), int(res[1]), int(res[2]));
    for (auto it = grid->tree().cbeginValueAll(); it; ++it) {
        float v = *it;
        if (!(v > 0)) continue;
        openvdb::CoordBBox b;
        it.getBoundingBox(b);
        int64_t c0[3], c1[3];
        for (int a = 0; a < 3; ++a) {
            int64_t first = int64_t(b.min()[a]) - origin[a], last = int64_t(b.max()[a]) - origin[a];
            c0[a] = std::max<int64_t>(0, -floorDiv(-(first - 2 - B), B));  // ceil((first - 2 - B) / B)
            c1[a] = std::min<int64_t>(res[a] - 1, floorDiv(last + 1, B));
        }
        // A relative margin of 1e-5 covers the rounding of the float trilinear blend.
        float bound = v * scale * (1.0f + 1e-5f);
        for (int64_t k = c0[2]; k <= c1[2]; ++k)
            for (int64_t j = c0[1]; j <= c1[1]; ++j)
                for (int64_t i = c0[0]; i <= c1[0]; ++i) {
                    float& cell = maj.at(int(i), int(j), int(k));
                    cell = std::max(cell, bound);
                }
    }
    maj.finish();
    impl->majorants = std::move(maj);
    if (budget) {
        // What the grid adds to the tree: the majorant cells, and the dense copy the constructor
        // keeps for lookups when the positive voxels' box (plus its border) has at most
        // kMaxDenseVoxels voxels. Larger sparse grids stay sparse; the active voxels' count and
        // box decide which.
        uint64_t lattice = 1;
        for (int a = 0; a < 3; ++a)  // saturates: each edge is below 2^33
            lattice = std::min<uint64_t>(lattice * uint64_t(int64_t(hi[a]) - int64_t(lo[a]) + 3), uint64_t(1) << 30);
        const bool dense = lattice <= VdbDensityGrid::kMaxDenseVoxels;
        budget->reserve(uint64_t(res[0] * res[1] * res[2]) * sizeof(float) + (dense ? lattice * sizeof(float) : 0),
                        label + " (" + std::to_string(impl->activeVoxels) + " active voxels" +
                            (dense ? ", a dense copy of " + std::to_string(lattice) + " voxels" : "") +
                            " and its majorant grid)");
    }
    return std::make_shared<const VdbDensityGrid>(std::move(impl));
}

VdbDensityGrid::VdbDensityGrid(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {
    if (!m_impl->empty) m_impl->hasDense = denseVolume(&m_impl->dense, kMaxDenseVoxels);
}
VdbDensityGrid::~VdbDensityGrid() = default;

std::shared_ptr<const VdbDensityGrid> VdbDensityGrid::load(const VdbGridSource& source,
                                                           const std::function<void(const std::string&)>& notice,
                                                           LoadBudget* budget) {
    initializeOpenVdb();
    const std::string where = "vdb file '" + source.file + "'";
    const VdbFileIndex file = readVdbFileIndex(source.file);
    const std::vector<VdbFileGrid>& grids = file.grids;
    // Grids sharing a name are told apart as name[k], k counted in file order.
    auto sameName = [&](const std::string& name) {
        std::vector<size_t> at;
        for (size_t i = 0; i < grids.size(); ++i)
            if (grids[i].name == name) at.push_back(i);
        return at;
    };
    std::ostringstream list;
    for (size_t i = 0; i < grids.size(); ++i) {
        const std::string& name = grids[i].name;
        std::vector<size_t> same = sameName(name);
        std::string label = name;
        if (same.size() > 1) label += "[" + std::to_string(std::find(same.begin(), same.end(), i) - same.begin()) + "]";
        list << (i ? ", " : "") << "'" << label << "' (" << grids[i].valueType() << ")";
    }
    std::string available = grids.empty() ? "the file holds no grids" : "grids in the file: " + list.str();

    std::string name = source.grid;
    long index = -1;  // -1: no [k] given
    std::smatch m;
    static const std::regex kIndexed(R"(^(.*)\[(\d{1,6})\]$)");
    if (std::regex_match(source.grid, m, kIndexed) && sameName(source.grid).empty()) {
        name = m[1];
        index = std::stol(m[2]);
    }
    if (name.empty()) {
        name = "density";
        std::vector<size_t> d = sameName(name);
        if (d.empty() || !grids[d[0]].isFloat()) {
            bool found = false;  // a grid's name may be "" (OpenVDB allows unnamed grids)
            for (const VdbFileGrid& g : grids)
                if (g.isFloat()) {
                    name = g.name;
                    found = true;
                    break;
                }
            if (!found) throw Error(where + ": no float grid to use as density (" + available + ")");
        }
    }
    std::vector<size_t> candidates = sameName(name);
    if (candidates.empty()) throw Error(where + ": no grid named '" + name + "' (" + available + ")");
    if (index >= long(candidates.size()))
        throw Error(where + ": '" + source.grid + "' asks for grid " + std::to_string(index + 1) + " named '" + name +
                    "', the file holds " + std::to_string(candidates.size()) + " (" + available + ")");
    if (index < 0 && candidates.size() > 1) {
        std::string line = where + ": " + std::to_string(candidates.size()) + " grids are named '" + name +
                           "'; using the first ('" + name + "[0]'); choose another with \"grid\": \"" + name +
                           "[1]\" (up to [" + std::to_string(candidates.size() - 1) + "]) in the medium's density";
        if (notice)
            notice(line);
        else
            std::fprintf(stderr, "tyndall: %s\n", line.c_str());
    }
    const size_t pick = candidates[size_t(std::max(index, 0L))];
    const VdbFileGrid& meta = grids[pick];
    const std::string chosen = candidates.size() > 1 ? name + "[" + std::to_string(std::max(index, 0L)) + "]" : name;
    const std::string at = where + ": grid '" + chosen + "'";
    if (!meta.isFloat()) throw Error(at + " holds " + meta.valueType() + " values; a density grid must hold float");
    if (meta.gridClass == openvdb::GridBase::gridClassToString(openvdb::GRID_LEVEL_SET))
        throw Error(at +
                    " is a level set (signed distance), not a density; convert it to a fog volume "
                    "(e.g. openvdb::tools::sdfToFogVolume or Houdini's VDB Convert)");
    openvdb::GridBase::Ptr base = readVdbGrid(file, pick, budget);
    if (!base->isType<openvdb::FloatGrid>()) throw Error(at + ": damaged: its tree is not a float tree");
    if (base->getGridClass() == openvdb::GRID_LEVEL_SET)
        throw Error(at + " is a level set (signed distance), not a density; convert it to a fog volume");
    try {
        openvdb::FloatGrid::ConstPtr grid = openvdb::gridConstPtrCast<openvdb::FloatGrid>(base);
        const float background = grid->background();
        if (source.ambientBackground && background > 0.0f && std::isfinite(background)) {
            // The background's stored copies (inactive tiles and voxels) become 0 first, then every
            // value is its excess over the background.
            openvdb::FloatGrid::Ptr shifted = grid->deepCopy();
            openvdb::tools::changeBackground(shifted->tree(), 0.0f);
            for (auto it = shifted->tree().beginValueAll(); it; ++it) it.setValue(std::max(*it - background, 0.0f));
            shifted->tree().prune();
            return makeVdbDensityGrid(shifted, source.transform, source.scale, at, kMajorantBlock, budget, background);
        }
        return makeVdbDensityGrid(grid, source.transform, source.scale, at, kMajorantBlock, budget);
    } catch (const openvdb::Exception& e) {
        throw Error(at + ": damaged: " + e.what());
    }
}

std::shared_ptr<const VdbDensityGrid> VdbDensityGrid::fromDense(const int dims[3], const std::vector<float>& values,
                                                                const Affine3& indexToWorld, const std::string& label,
                                                                int majorantBlock) {
    initializeOpenVdb();
    if (dims[0] < 0 || dims[1] < 0 || dims[2] < 0 || values.size() != size_t(dims[0]) * dims[1] * dims[2])
        throw Error(label + ": dense block size does not match its dimensions");
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    if (!(std::abs(indexToWorld.determinant()) > 0)) throw Error(label + ": index-to-world transform is singular");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(affineToOpenVdb(indexToWorld)));
    auto acc = grid->getAccessor();
    for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
            for (int i = 0; i < dims[0]; ++i) {
                float v = values[(size_t(k) * dims[1] + j) * dims[0] + i];
                if (v > 0) acc.setValue(openvdb::Coord(i, j, k), v);
            }
    grid->tree().prune();
    return makeVdbDensityGrid(grid, Affine3(), 1.0f, label, majorantBlock);
}

float VdbDensityGrid::density(const Vec3& p) const {
    const Impl& g = *m_impl;
    if (g.empty || !g.worldBounds.contains(p)) return 0.0f;
    if (g.hasDense) return g.dense.sample(p);
    Vec3 x = g.worldToIndex.point(p);
    float v = openvdb::tools::BoxSampler::sample(accessorFor(g), openvdb::Vec3R(x.x, x.y, x.z));
    return std::max(v, 0.0f) * g.scale;
}

Bounds3 VdbDensityGrid::bounds() const {
    return m_impl->worldBounds;
}
float VdbDensityGrid::majorant(const Ray& ray) const {
    return m_impl->empty ? 0.0f : m_impl->majorants.maxAlong(ray, ray.tMin, ray.tMax);
}
const MajorantGrid* VdbDensityGrid::majorantGrid() const {
    return &m_impl->majorants;
}
float VdbDensityGrid::maxDensity() const {
    return m_impl->maxDensity;
}
uint64_t VdbDensityGrid::contentHash(uint64_t h) const {
    const Impl& m = *m_impl;
    auto mix = [&h](const void* data, size_t size) {
        const uint64_t c = checksum64(data, size);
        h = fnv1a(&c, sizeof c, h);
    };
    const float params[2] = {m.scale, m.background};
    mix(params, sizeof params);
    mix(&m.indexToWorld, sizeof m.indexToWorld);
    const openvdb::FloatTree& tree = m.grid->tree();
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        const openvdb::Coord o = leaf->origin();
        const int32_t origin[3] = {o.x(), o.y(), o.z()};
        mix(origin, sizeof origin);
        const auto& mask = leaf->getValueMask();
        uint64_t words[mask.WORD_COUNT];
        for (openvdb::Index w = 0; w < mask.WORD_COUNT; ++w) words[w] = mask.template getWord<uint64_t>(w);
        mix(words, sizeof words);
        mix(leaf->buffer().data(), leaf->buffer().size() * sizeof(float));
    }
    // Tiles: the value iterator above the leaf level.
    auto tile = tree.cbeginValueAll();
    tile.setMaxDepth(openvdb::FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
    for (; tile; ++tile) {
        openvdb::CoordBBox b;
        tile.getBoundingBox(b);
        const int32_t box[7] = {b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z(),
                                tile.isValueOn() ? 1 : 0};
        mix(box, sizeof box);
        const float v = *tile;
        mix(&v, sizeof v);
    }
    return h;
}

float VdbDensityGrid::meanDensity() const {
    return m_impl->meanDensity;
}
double VdbDensityGrid::integratedDensity() const {
    return m_impl->integratedDensity;
}
const std::string& VdbDensityGrid::label() const {
    return m_impl->label;
}
const std::string& VdbDensityGrid::gridName() const {
    return m_impl->name;
}
float VdbDensityGrid::background() const {
    return m_impl->background;
}
uint64_t VdbDensityGrid::activeVoxelCount() const {
    return m_impl->activeVoxels;
}
int VdbDensityGrid::majorantBlock() const {
    return m_impl->majorantBlock;
}
const Affine3& VdbDensityGrid::indexToWorld() const {
    return m_impl->indexToWorld;
}
const Affine3& VdbDensityGrid::worldToIndex() const {
    return m_impl->worldToIndex;
}

bool VdbDensityGrid::denseVolume(DensityVolume* out, size_t maxVoxels) const {
    const Impl& g = *m_impl;
    *out = DensityVolume();
    if (g.empty) return true;  // no lattice points: 0 everywhere
    // The positive voxels plus a zero border (the trilinear support), lattice point (0,0,0) at
    // index lo; the scale folded into the values.
    const openvdb::Coord lo = g.positiveBox.min() - openvdb::Coord(1), hi = g.positiveBox.max() + openvdb::Coord(1);
    const uint64_t nx = uint64_t(hi.x() - lo.x() + 1), ny = uint64_t(hi.y() - lo.y() + 1),
                   nz = uint64_t(hi.z() - lo.z() + 1);
    if (nx * ny * nz > uint64_t(maxVoxels)) return false;
    out->nx = int(nx);
    out->ny = int(ny);
    out->nz = int(nz);
    out->voxels.resize(out->voxelCount());
    Accessor& acc = accessorFor(g);
    size_t n = 0;
    for (int k = lo.z(); k <= hi.z(); ++k)
        for (int j = lo.y(); j <= hi.y(); ++j)
            for (int i = lo.x(); i <= hi.x(); ++i)
                out->voxels[n++] = std::max(acc.getValue(openvdb::Coord(i, j, k)), 0.0f) * g.scale;
    Affine3 shift = Affine3::scaleTranslate(Vec3(1.0f), Vec3(-float(lo.x()), -float(lo.y()), -float(lo.z())));
    Affine3 w = shift * g.worldToIndex;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) out->worldToIndex[r][c] = w.m[r][c];
    return true;
}

}  // namespace tyndall
