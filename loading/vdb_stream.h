#pragma once
// What OpenVDB reads a grid from (loading/vdb_file.cpp): a stream over a copy of the grid's bytes
// that fails at the first read past them. Private to loading/.
//
// vdb_stream.cpp also replaces OpenVDB's readers of compressed blocks (io::bloscFromStream and
// io::unzipFromStream, called from the tree templates that Tyndall instantiates; this definition
// is the one the executable links). OpenVDB 10's take a block's size from the file and trust it:
// a negative size ("stored uncompressed") is read into the destination before it is compared
// with the destination's size (a heap overflow on a damaged file), a positive one is allocated
// before it is compared with the bytes there are, and blosc is given a buffer without its length.
// These check every size (against the destination, the bytes left, blosc's own header) before
// anything is read or allocated, and throw std::runtime_error for a damaged block; valid files read
// exactly as before.
#include <cstddef>
#include <streambuf>

namespace tyndall {

class VdbMemoryBuffer : public std::streambuf {
public:
    VdbMemoryBuffer(char* data, size_t size);
    /// Bytes between the read position and the end.
    size_t left() const { return size_t(egptr() - gptr()); }

protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override;
    pos_type seekpos(pos_type pos, std::ios_base::openmode) override;

private:
    pos_type seekTo(off_type p);
};

}  // namespace tyndall
