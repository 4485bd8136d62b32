#include "core/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/load_budget.h"

namespace tyndall {

namespace {
constexpr char kCheckpointMagic[8] = {'T', 'Y', 'N', 'C', 'K', 'P', 'T', '\x01'};

template <class T>
void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// Reads fixed-size values from the file's bytes, failing with the file's name when they run out.
class Reader {
public:
    Reader(const std::string& bytes, size_t end, const std::string& file) : m_b(bytes), m_end(end), m_file(file) {}
    template <class T>
    T get() {
        T v;
        std::memcpy(&v, take(sizeof(T)), sizeof(T));
        return v;
    }
    const char* take(size_t n) {
        if (n > m_end - m_at)
            throw Error(m_file + ": malformed checkpoint (a block of " + std::to_string(n) + " bytes at byte " +
                        std::to_string(m_at) + " runs past the end, " + std::to_string(m_end - m_at) + " bytes left)");
        const char* p = m_b.data() + m_at;
        m_at += n;
        return p;
    }
    bool done() const { return m_at == m_end; }

private:
    const std::string& m_b;
    size_t m_end, m_at = 0;
    std::string m_file;
};

std::string systemError() {
    return std::strerror(errno);
}
}  // namespace

uint64_t fnv1a(const void* data, size_t size, uint64_t hash) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
    return hash;
}

uint64_t checksum64(const void* data, size_t size) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    uint64_t hash = 0xcbf29ce484222325ull;
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        uint64_t word;
        std::memcpy(&word, p + i, 8);
        hash = (hash ^ word) * 0x100000001b3ull;
    }
    return fnv1a(p + i, size - i, hash);
}

const Accumulator& Checkpoint::layer(const std::string& name, const std::string& file) const {
    for (const auto& [n, acc] : layers)
        if (n == name) return acc;
    throw Error(file + ": the checkpoint holds no '" + name + "' layer");
}

std::string serializeCheckpoint(const Checkpoint& c) {
    std::string out(kCheckpointMagic, sizeof kCheckpointMagic);
    std::string header = c.header.dump();
    size_t total = sizeof kCheckpointMagic + 8 + header.size() + 4 + 8;
    for (const auto& [name, acc] : c.layers) total += 4 + name.size() + 24 + acc.sums().size() * sizeof(double);
    out.reserve(total);
    put(out, uint64_t(header.size()));
    out += header;
    put(out, uint32_t(c.layers.size()));
    for (const auto& [name, acc] : c.layers) {
        put(out, uint32_t(name.size()));
        out += name;
        put(out, int32_t(acc.width()));
        put(out, int32_t(acc.height()));
        put(out, acc.passCount());
        put(out, acc.rejectedSamples());
        out.append(reinterpret_cast<const char*>(acc.sums().data()), acc.sums().size() * sizeof(double));
    }
    put(out, checksum64(out.data(), out.size()));
    return out;
}

Checkpoint parseCheckpoint(const std::string& bytes, const std::string& file) {
    if (bytes.size() < sizeof kCheckpointMagic ||
        std::memcmp(bytes.data(), kCheckpointMagic, sizeof kCheckpointMagic) != 0)
        throw Error(file + ": not a Tyndall checkpoint (it does not start with the checkpoint signature)");
    if (bytes.size() < sizeof kCheckpointMagic + 8 + 4 + 8)
        throw Error(file + ": truncated checkpoint (" + std::to_string(bytes.size()) + " bytes)");
    const size_t body = bytes.size() - 8;
    uint64_t stored;
    std::memcpy(&stored, bytes.data() + body, 8);
    if (stored != checksum64(bytes.data(), body))
        throw Error(file + ": truncated or damaged checkpoint (checksum mismatch); it cannot be resumed");
    Reader r(bytes, body, file);
    r.take(sizeof kCheckpointMagic);
    Checkpoint c;
    uint64_t headerSize = r.get<uint64_t>();
    if (headerSize > body) throw Error(file + ": malformed checkpoint (header size)");
    const char* h = r.take(size_t(headerSize));
    try {
        c.header = nlohmann::json::parse(h, h + headerSize);
    } catch (const std::exception& e) {
        throw Error(file + ": malformed checkpoint header: " + e.what());
    }
    uint32_t count = r.get<uint32_t>();
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t nameSize = r.get<uint32_t>();
        std::string name(r.take(nameSize), nameSize);
        int32_t w = r.get<int32_t>(), hgt = r.get<int32_t>();
        uint64_t passes = r.get<uint64_t>(), rejected = r.get<uint64_t>();
        if (w <= 0 || hgt <= 0 || w > 65536 || hgt > 65536)
            throw Error(file + ": malformed checkpoint (layer '" + name + "' is " + std::to_string(w) + "x" +
                        std::to_string(hgt) + ")");
        // The declared size is checked against the bytes present before anything is allocated.
        const size_t values = size_t(w) * size_t(hgt) * 3;
        const char* data = r.take(values * sizeof(double));
        std::vector<double> sums(values);
        std::memcpy(sums.data(), data, values * sizeof(double));
        c.layers.emplace_back(std::move(name), Accumulator::fromSums(w, hgt, passes, rejected, std::move(sums)));
    }
    if (!r.done()) throw Error(file + ": malformed checkpoint (bytes after the last layer)");
    return c;
}

void writeFileAtomically(const std::string& path, const std::string& bytes, const std::function<void()>& midWrite) {
    namespace fs = std::filesystem;
    const std::string tmp = path + ".tmp";
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw Error("checkpoint '" + path + "': cannot create '" + tmp + "': " + systemError());
    auto writeAll = [&](const char* p, size_t n) {
        while (n > 0) {
            ssize_t k = ::write(fd, p, n);
            if (k < 0 && errno == EINTR) continue;
            if (k <= 0) {
                std::string why = systemError();
                ::close(fd);
                ::unlink(tmp.c_str());
                throw Error("checkpoint '" + path + "': writing '" + tmp + "' failed: " + why + " (disk full?)");
            }
            p += k;
            n -= size_t(k);
        }
    };
    const size_t half = bytes.size() / 2;
    writeAll(bytes.data(), half);
    if (midWrite) midWrite();
    writeAll(bytes.data() + half, bytes.size() - half);
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        std::string why = systemError();
        ::unlink(tmp.c_str());
        throw Error("checkpoint '" + path + "': flushing '" + tmp + "' failed: " + why);
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        std::string why = systemError();
        ::unlink(tmp.c_str());
        throw Error("checkpoint '" + path + "': renaming '" + tmp + "' over it failed: " + why);
    }
    // The rename itself is durable once the directory is synced.
    fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
    int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

void saveCheckpoint(const std::string& path, const Checkpoint& checkpoint, const std::function<void()>& midWrite) {
    writeFileAtomically(path, serializeCheckpoint(checkpoint), midWrite);
}

Checkpoint loadCheckpoint(const std::string& path, const LoadBudget* budget) {
    namespace fs = std::filesystem;
    const std::string where = "checkpoint '" + path + "'";
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(where + ": cannot be opened (no such file?)");
    if (!fs::is_regular_file(path, ec)) throw Error(where + ": not a regular file");
    const uint64_t length = fs::file_size(path, ec);
    if (ec) throw Error(where + ": cannot be read: " + ec.message());
    if (budget) budget->check(2 * length, where + " (" + describeBytes(length) + ", read and parsed)");
    std::ifstream in(path, std::ios::binary);
    std::string bytes(size_t(length), '\0');
    if (!in || !in.read(bytes.data(), std::streamsize(length)))
        throw Error(where + ": cannot be read (" + systemError() + ")");
    return parseCheckpoint(bytes, where);
}

}  // namespace tyndall
