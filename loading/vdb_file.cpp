#include "loading/vdb_file.h"

#include <openvdb/io/Stream.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>

#include "core/error.h"
#include "core/load_budget.h"
#include "loading/vdb_stream.h"

namespace tyndall {

namespace {

constexpr uint32_t kGridInstancing = 216;  // OPENVDB_FILE_VERSION_GRID_INSTANCING
constexpr uint32_t kBoostUuid = 218;       // OPENVDB_FILE_VERSION_BOOST_UUID: 36-character uuid
constexpr uint32_t kSelectiveCompression = 220;
constexpr uint32_t kNodeMaskCompression = 222;  // per-grid compression flags
constexpr char kHalfSuffix[] = "_HalfFloat";
constexpr char kUniqueSeparator = '\x1e';
constexpr char kDelayedLoadType[] = "__delayedload";
constexpr char kOpaqueType[] = "__tyndallskip";  // unregistered, as long as kDelayedLoadType
static_assert(sizeof kDelayedLoadType == sizeof kOpaqueType);

/// Reads the file's bytes at known offsets; every read is checked against the file's length and
/// a short one is reported as the file ending inside `what`.
class FileCursor {
public:
    FileCursor(const std::string& path, const std::string& where, uint64_t size)
        : m_in(path, std::ios::binary), m_where(where), m_size(size) {
        if (!m_in) throw Error(m_where + ": cannot be opened (permissions?)");
    }
    uint64_t pos() const { return m_pos; }
    uint64_t size() const { return m_size; }
    void seek(uint64_t p) { m_pos = p; }

    /// Throws unless `n` bytes from here lie inside the file (and inside `limit`, the end of the
    /// grid being read, when given).
    void need(uint64_t n, const std::string& what, uint64_t limit = UINT64_MAX) const {
        if (m_pos <= m_size && n <= m_size - m_pos && (limit == UINT64_MAX || (m_pos <= limit && n <= limit - m_pos)))
            return;
        if (limit != UINT64_MAX && limit <= m_size)
            throw Error(m_where + ": damaged: " + what + " at byte " + std::to_string(m_pos) + " needs " +
                        std::to_string(n) + " bytes, past the end of its grid at byte " + std::to_string(limit));
        throw Error(m_where + ": truncated: the file ends at byte " + std::to_string(m_size) + " inside " + what +
                    " (which needs " + std::to_string(n) + " bytes from byte " + std::to_string(m_pos) +
                    "); an interrupted copy? Copy the file again");
    }
    void read(void* out, uint64_t n, const std::string& what, uint64_t limit = UINT64_MAX) {
        need(n, what, limit);
        m_in.seekg(std::streamoff(m_pos));
        m_in.read(static_cast<char*>(out), std::streamsize(n));
        if (!m_in) throw Error(m_where + ": read error at byte " + std::to_string(m_pos));
        m_pos += n;
    }
    template <typename T>
    T value(const std::string& what, uint64_t limit = UINT64_MAX) {
        T v;
        read(&v, sizeof v, what, limit);
        return v;
    }
    /// OpenVDB's string: a uint32 length, then the characters. Longer than `maxKeep` is skipped
    /// (the characters are not needed) and "" returned.
    std::string string(const std::string& what, uint64_t limit = UINT64_MAX, uint32_t maxKeep = 4096) {
        uint32_t n = value<uint32_t>(what + " (its length)", limit);
        if (n > maxKeep) {
            need(n, what, limit);
            m_pos += n;
            return {};
        }
        std::string s(n, '\0');
        if (n) read(s.data(), n, what, limit);
        return s;
    }
    void skip(uint64_t n, const std::string& what, uint64_t limit = UINT64_MAX) {
        need(n, what, limit);
        m_pos += n;
    }
    /// Copies bytes [from, to) (inside the file) into `out`.
    void copy(uint64_t from, uint64_t to, std::string& out) {
        m_pos = from;
        const size_t at = out.size();
        out.resize(at + size_t(to - from));
        read(out.data() + at, to - from, "a grid");
    }

private:
    std::ifstream m_in;
    std::string m_where;
    uint64_t m_size = 0, m_pos = 0;
};

std::string displayName(const std::string& unique) {
    size_t sep = unique.find(kUniqueSeparator);
    return sep == std::string::npos ? unique : unique.substr(0, sep);
}

/// OpenVDB reads a value of a fixed-size metadata type as sizeof(T) bytes whatever size the file
/// records for it; a record that says otherwise would send OpenVDB's reading out of step with
/// this parser (into bytes it takes for lengths). Throws for such a record.
void checkMetadataSize(const std::string& type, uint32_t bytes, const std::string& what) {
    using namespace openvdb;
    static const std::pair<std::string, uint32_t> kFixed[] = {
        {typeNameAsString<bool>(), sizeof(bool)},   {typeNameAsString<double>(), sizeof(double)},
        {typeNameAsString<float>(), sizeof(float)}, {typeNameAsString<int32_t>(), sizeof(int32_t)},
        {typeNameAsString<int64_t>(), sizeof(int64_t)}, {typeNameAsString<Vec2i>(), sizeof(Vec2i)},
        {typeNameAsString<Vec2s>(), sizeof(Vec2s)}, {typeNameAsString<Vec2d>(), sizeof(Vec2d)},
        {typeNameAsString<Vec3i>(), sizeof(Vec3i)}, {typeNameAsString<Vec3s>(), sizeof(Vec3s)},
        {typeNameAsString<Vec3d>(), sizeof(Vec3d)}, {typeNameAsString<Vec4i>(), sizeof(Vec4i)},
        {typeNameAsString<Vec4s>(), sizeof(Vec4s)}, {typeNameAsString<Vec4d>(), sizeof(Vec4d)},
        {typeNameAsString<Mat4s>(), sizeof(Mat4s)}, {typeNameAsString<Mat4d>(), sizeof(Mat4d)}};
    for (const auto& [name, size] : kFixed)
        if (type == name && bytes != size)
            throw Error(what + ": damaged: records " + std::to_string(bytes) + " bytes for a value of type '" + type +
                        "', which has " + std::to_string(size));
}

/// A grid's metadata (OpenVDB's MetaMap: count, then name, type name, byte size, value), keeping
/// the few entries that say what the grid is and how large.
void readGridMetadata(FileCursor& in, VdbFileGrid& g, const std::string& at) {
    const uint64_t end = g.endPos;
    const int32_t count = in.value<int32_t>(at + ": metadata count", end);
    if (count < 0) throw Error(at + ": damaged: negative metadata count");
    for (int32_t k = 0; k < count; ++k) {
        const std::string entry = at + ": metadata entry " + std::to_string(k);
        const std::string name = in.string(entry + " name", end);
        const std::string type = in.string(entry + " type", end);
        // OpenVDB's delayed-load table sizes its arrays from counts inside it, unchecked: the copy
        // handed to OpenVDB renames its type so that it is read as opaque bytes (it is not used).
        if (type == kDelayedLoadType) g.opaqueTypeAt.push_back(in.pos() - type.size());
        const uint32_t bytes = in.value<uint32_t>(entry + " size", end);
        const std::string what = at + ": metadata '" + name + "'";
        checkMetadataSize(type, bytes, what);
        if (name == "class" && type == "string" && bytes <= 256) {
            g.gridClass.assign(bytes, '\0');
            if (bytes) in.read(g.gridClass.data(), bytes, what, end);
        } else if ((name == "file_mem_bytes" || name == "file_voxel_count") && type == "int64" && bytes == 8) {
            (name == "file_mem_bytes" ? g.memBytes : g.voxelCount) = in.value<int64_t>(what, end);
        } else if ((name == "file_bbox_min" || name == "file_bbox_max") && type == "vec3i" && bytes == 12) {
            auto& box = name == "file_bbox_min" ? g.bboxMin : g.bboxMax;
            in.read(box.data(), 12, what, end);
            if (name == "file_bbox_max") g.hasBBox = true;
        } else {
            in.skip(bytes, what, end);
        }
    }
}

uint64_t fileSize(const std::string& path, const std::string& where) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(where + ": no such file");
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(where + ": cannot be read (" + ec.message() + ")");
    return size;
}

}  // namespace

std::string VdbFileGrid::valueType() const {
    if (openvdb::GridBase::isRegistered(type)) return openvdb::GridBase::createGrid(type)->valueType();
    return type;
}

bool VdbFileGrid::isFloat() const {
    return type == openvdb::FloatGrid::gridType();
}

VdbFileIndex readVdbFileIndex(const std::string& path) {
    const std::string where = "vdb file '" + path + "'";
    VdbFileIndex index;
    index.path = path;
    index.fileBytes = fileSize(path, where);
    if (index.fileBytes == 0) throw Error(where + ": is empty (0 bytes)");
    FileCursor in(path, where, index.fileBytes);

    // The header (openvdb::io::Archive::readHeader).
    int64_t magic = 0;
    in.read(&magic, std::min<uint64_t>(8, index.fileBytes), "the header");
    if (index.fileBytes < 8 || (magic & 0xFFFFFFFF) != openvdb::OPENVDB_MAGIC)
        throw Error(where + ": cannot be read as an OpenVDB file: it does not begin with the VDB magic number");
    if (magic != openvdb::OPENVDB_MAGIC) throw Error(where + ": damaged: bad VDB magic number");
    in.seek(8);
    index.version = in.value<uint32_t>("the header (format version)");
    if (index.version < 213 || index.version > openvdb::OPENVDB_FILE_VERSION)
        throw Error(where + ": file format version " + std::to_string(index.version) +
                    " is not one this reader knows (" + "213.." + std::to_string(openvdb::OPENVDB_FILE_VERSION) + ")" +
                    (index.version > 100000 ? "; a damaged file?" : "; re-save it with a current OpenVDB"));
    in.skip(8, "the header (library version)");
    const bool hasOffsets = in.value<char>("the header (grid offsets flag)") != 0;
    if (index.version >= kSelectiveCompression && index.version < kNodeMaskCompression)
        in.skip(1, "the header (compression flag)");
    in.skip(index.version >= kBoostUuid ? 36 : 16, "the header (file id)");
    if (!hasOffsets)
        throw Error(where +
                    ": was written as a stream without grid offsets, which this reader does not accept; "
                    "save it with openvdb::io::File (Houdini and vdb_tool do)");

    // The file's metadata: skipped, every length checked.
    const int32_t metaCount = in.value<int32_t>("the file metadata (its count)");
    if (metaCount < 0) throw Error(where + ": damaged: negative file metadata count");
    for (int32_t k = 0; k < metaCount; ++k) {
        const std::string what = "file metadata entry " + std::to_string(k);
        in.string(what + " (its name)");
        const std::string type = in.string(what + " (its type)");
        const uint32_t bytes = in.value<uint32_t>(what + " (its size)");
        checkMetadataSize(type, bytes, where + ": " + what);
        in.skip(bytes, what);
    }

    index.gridCountPos = in.pos();
    const int32_t gridCount = in.value<int32_t>("the grid count");
    if (gridCount < 0) throw Error(where + ": damaged: negative grid count");
    for (int32_t i = 0; i < gridCount; ++i) {
        VdbFileGrid g;
        const std::string desc = "the descriptor of grid " + std::to_string(i);
        g.descriptorPos = in.pos();
        g.uniqueName = in.string(desc + " (its name)");
        g.name = displayName(g.uniqueName);
        g.type = in.string(desc + " (its type)");
        const size_t hs = sizeof(kHalfSuffix) - 1;
        if (g.type.size() > hs && g.type.compare(g.type.size() - hs, hs, kHalfSuffix) == 0)
            g.type.resize(g.type.size() - hs);
        if (index.version >= kGridInstancing) g.instanceParent = in.string(desc + " (its instance parent)");
        int64_t pos[3];
        in.read(pos, sizeof pos, desc + " (its offsets)");
        const std::string at = where + ": grid '" + g.name + "'";
        if (pos[0] != int64_t(in.pos()) || pos[1] < pos[0] || pos[2] < pos[1])
            throw Error(at + ": damaged: its descriptor's offsets (" + std::to_string(pos[0]) + ", " +
                        std::to_string(pos[1]) + ", " + std::to_string(pos[2]) + ") do not fit together");
        g.gridPos = uint64_t(pos[0]);
        g.blockPos = uint64_t(pos[1]);
        g.endPos = uint64_t(pos[2]);
        if (g.endPos > index.fileBytes)
            throw Error(at + ": truncated: the grid ends at byte " + std::to_string(g.endPos) + " but the file has " +
                        std::to_string(index.fileBytes) + " bytes; an interrupted copy? Copy the file again");
        if (index.version >= kNodeMaskCompression) in.skip(4, at + ": compression flags", g.endPos);
        readGridMetadata(in, g, at);
        // The transform's type name (OpenVDB sizes a string from its length before reading it).
        if (index.version >= kGridInstancing) in.string(at + ": transform type", g.endPos);
        in.seek(g.endPos);
        index.grids.push_back(std::move(g));
    }
    return index;
}

openvdb::GridBase::Ptr readVdbGrid(const VdbFileIndex& index, size_t i, LoadBudget* budget) {
    const VdbFileGrid& g = index.grids.at(i);
    const std::string at = "vdb file '" + index.path + "': grid '" + g.name + "'";
    // The grid and, first, the one whose tree it shares.
    std::vector<size_t> parts;
    if (!g.instanceParent.empty()) {
        for (size_t k = 0; k < index.grids.size() && parts.empty(); ++k)
            if (index.grids[k].uniqueName == g.instanceParent) parts.push_back(k);
        if (parts.empty()) throw Error(at + ": damaged: shares the tree of a grid the file does not hold");
        if (!index.grids[parts[0]].instanceParent.empty()) throw Error(at + ": damaged: an instance of an instance");
    }
    parts.push_back(i);

    uint64_t fileBytes = index.gridCountPos + 4;
    for (size_t k : parts) fileBytes += index.grids[k].endPos - index.grids[k].descriptorPos;
    const uint64_t declared = g.memBytes > 0 ? uint64_t(g.memBytes) : 0;
    if (budget) {
        budget->check(fileBytes, at + " (its bytes in the file)");
        budget->reserve(std::max(declared, fileBytes), at + (declared ? " (the memory it records)" : ""));
    }

    // A stand-alone copy: the header, a grid count, then each part with its offsets moved.
    std::string bytes;
    bytes.reserve(size_t(fileBytes));
    FileCursor in(index.path, "vdb file '" + index.path + "'", index.fileBytes);
    in.copy(0, index.gridCountPos, bytes);
    const int32_t count = int32_t(parts.size());
    bytes.append(reinterpret_cast<const char*>(&count), 4);
    for (size_t k : parts) {
        const VdbFileGrid& p = index.grids[k];
        const int64_t shift = int64_t(bytes.size()) - int64_t(p.descriptorPos);
        in.copy(p.descriptorPos, p.endPos, bytes);
        const size_t offsets = bytes.size() - size_t(p.endPos - p.gridPos) - 24;
        int64_t pos[3] = {int64_t(p.gridPos) + shift, int64_t(p.blockPos) + shift, int64_t(p.endPos) + shift};
        std::memcpy(bytes.data() + offsets, pos, sizeof pos);
        for (uint64_t at : p.opaqueTypeAt)
            std::memcpy(bytes.data() + int64_t(at) + shift, kOpaqueType, sizeof kOpaqueType - 1);
    }

    openvdb::GridBase::Ptr grid;
    try {
        VdbMemoryBuffer buffer(bytes.data(), bytes.size());
        std::istream stream(&buffer);
        stream.exceptions(std::ios::failbit | std::ios::badbit);
        openvdb::io::Stream reader(stream, /*delayLoad=*/false);
        openvdb::GridPtrVecPtr grids = reader.getGrids();
        if (!grids || grids->size() != parts.size() || !grids->back())
            throw Error(at + ": damaged: OpenVDB read " + std::to_string(grids ? grids->size() : 0) + " grids");
        grid = grids->back();
    } catch (const Error&) {
        throw;
    } catch (const std::ios_base::failure&) {
        throw Error(at + ": damaged: its data ends before its tree does (a cut or corrupted file)");
    } catch (const std::bad_alloc&) {
        throw Error(at + ": damaged: reading it asked for more memory than the machine gives (corrupted sizes?)");
    } catch (const std::exception& e) {
        throw Error(at + ": damaged: OpenVDB cannot read it (" + std::string(e.what()) + ")");
    }
    if (budget) {
        const uint64_t used = uint64_t(grid->memUsage());
        if (used > std::max(declared, fileBytes))
            budget->reserve(used - std::max(declared, fileBytes), at + " (its memory once read)");
    }
    return grid;
}

}  // namespace tyndall
