#pragma once
// Strict reading of OpenVDB files, in front of OpenVDB's own reader. OpenVDB trusts its input:
// given a file cut short (an interrupted copy) it goes on reading counts and masks from bytes that
// are not there and can allocate without bound, differently from run to run. Here:
// - the header, the file's metadata and every grid descriptor are parsed first, each length
//   checked against the bytes present; a grid whose recorded extent runs past the end of the file
//   is reported as truncated (both lengths named) before OpenVDB reads anything;
// - each grid's own metadata is read too (its class and the statistics OpenVDB records when it
//   writes: memory, active voxel count, active bounding box), so that a grid can be weighed
//   against the loading budget before it is read;
// - OpenVDB then reads one grid (and the grid whose tree it shares, if any) from a copy of just
//   its bytes, through a stream that throws at the first read past them: a damaged grid ends in an
//   Error, never in a runaway loop. OpenVDB's stream exceptions become Errors naming the file.
// Private to loading/ (includes OpenVDB).
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tyndall {

class LoadBudget;

/// One grid as the file describes it.
struct VdbFileGrid {
    std::string name;            ///< the grid's name (OpenVDB's "name\x1eN" suffix of duplicates removed)
    std::string uniqueName;      ///< as stored (tells duplicates and instance parents apart)
    std::string type;            ///< grid type, e.g. "Tree_float_5_4_3" ("_HalfFloat" removed)
    std::string instanceParent;  ///< unique name of the grid whose tree this one shares; empty = none
    uint64_t descriptorPos = 0;  ///< byte offsets in the file: descriptor, grid, leaf buffers, end
    uint64_t gridPos = 0, blockPos = 0, endPos = 0;
    // From the grid's metadata; absent when the writer did not record them.
    std::string gridClass;                        ///< "fog volume", "level set", ... ("" = unknown)
    int64_t memBytes = -1;                        ///< "file_mem_bytes": memory of the grid when written
    int64_t voxelCount = -1;                      ///< "file_voxel_count": active voxels
    bool hasBBox = false;                         ///< "file_bbox_min"/"file_bbox_max" present
    std::array<int32_t, 3> bboxMin{}, bboxMax{};  ///< active voxels' index bounds (inclusive)
    std::vector<uint64_t> opaqueTypeAt;  ///< metadata type names readVdbGrid hides from OpenVDB (file offsets)

    /// "float", "vec3s", ... when OpenVDB knows the type; else the type name.
    std::string valueType() const;
    bool isFloat() const;
};

struct VdbFileIndex {
    std::string path;
    uint64_t fileBytes = 0;
    uint32_t version = 0;       ///< file format version (OpenVDB 10 writes 224)
    uint64_t gridCountPos = 0;  ///< where the grid count is stored (the header ends there)
    std::vector<VdbFileGrid> grids;
};

/// Parses `path`'s header and grid descriptors (and each grid's metadata). Throws Error
/// "vdb file '<path>': ..." for a missing, empty or non-VDB file, a file cut short (naming where
/// it ends and what was expected past it), or descriptors that do not fit together. Files written
/// without grid offsets (OpenVDB's io::Stream to a file) cannot be indexed and are refused with a
/// message saying to save them with openvdb::io::File.
VdbFileIndex readVdbFileIndex(const std::string& path);

/// Reads grid `i` of an indexed file. `budget` (may be null) is asked first for the grid's
/// recorded memory ("file_mem_bytes", at least its bytes in the file), and after reading for any
/// memory it holds beyond that. Throws Error naming the file and grid for a damaged grid (any
/// OpenVDB error or a read past the grid's bytes).
openvdb::GridBase::Ptr readVdbGrid(const VdbFileIndex& index, size_t i, LoadBudget* budget);

}  // namespace tyndall
