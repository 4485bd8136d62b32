#include "core/accumulator.h"

#include <cmath>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace tyndall {

namespace {
constexpr char kAccumulatorMagic[8] = {'T', 'Y', 'N', 'A', 'C', 'C', '1', '\0'};
}

Accumulator::Accumulator(int width, int height)
    : m_width(width), m_height(height), m_sum(size_t(width) * size_t(height) * 3, 0.0) {}

void Accumulator::addPass(const Image& pass) {
    TYNDALL_CHECK(pass.width == m_width && pass.height == m_height, "pass image size differs from the accumulator");
    for (size_t i = 0; i < pass.pixels.size(); ++i) {
        const Rgb& p = pass.pixels[i];
        if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b)) {
            ++m_rejected;
            continue;
        }
        m_sum[3 * i + 0] += p.r;
        m_sum[3 * i + 1] += p.g;
        m_sum[3 * i + 2] += p.b;
    }
    ++m_passes;
}

void Accumulator::merge(const Accumulator& other) {
    TYNDALL_CHECK(other.m_width == m_width && other.m_height == m_height, "cannot merge accumulators of different sizes");
    for (size_t i = 0; i < m_sum.size(); ++i) m_sum[i] += other.m_sum[i];
    m_passes += other.m_passes;
    m_rejected += other.m_rejected;
}

Accumulator Accumulator::fromSums(int width, int height, uint64_t passes, uint64_t rejected, std::vector<double> sums) {
    if (width <= 0 || height <= 0 || sums.size() != size_t(width) * size_t(height) * 3)
        throw Error("accumulator state of " + std::to_string(sums.size()) + " values does not fit a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image");
    Accumulator acc;
    acc.m_width = width;
    acc.m_height = height;
    acc.m_passes = passes;
    acc.m_rejected = rejected;
    acc.m_sum = std::move(sums);
    return acc;
}

void Accumulator::reset() {
    std::fill(m_sum.begin(), m_sum.end(), 0.0);
    m_passes = 0;
    m_rejected = 0;
}

Image Accumulator::mean() const {
    Image img(m_width, m_height);
    if (m_passes == 0) return img;
    double inv = 1.0 / double(m_passes);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = Rgb(float(m_sum[3 * i] * inv), float(m_sum[3 * i + 1] * inv), float(m_sum[3 * i + 2] * inv));
    return img;
}

double Accumulator::meanAt(int x, int y, int c) const {
    if (m_passes == 0) return 0.0;
    return m_sum[(size_t(y) * m_width + x) * 3 + c] / double(m_passes);
}

void Accumulator::save(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error("cannot write accumulator checkpoint '" + path + "'");
    int32_t dims[2] = {m_width, m_height};
    out.write(kAccumulatorMagic, sizeof(kAccumulatorMagic));
    out.write(reinterpret_cast<const char*>(dims), sizeof(dims));
    out.write(reinterpret_cast<const char*>(&m_passes), sizeof(m_passes));
    out.write(reinterpret_cast<const char*>(m_sum.data()), std::streamsize(m_sum.size() * sizeof(double)));
    if (!out) throw Error("failed writing accumulator checkpoint '" + path + "' (disk full?)");
}

Accumulator Accumulator::load(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot open accumulator checkpoint '" + path + "'");
    char magic[8];
    int32_t dims[2];
    uint64_t passes = 0;
    in.read(magic, sizeof(magic));
    if (!in || std::memcmp(magic, kAccumulatorMagic, sizeof(kAccumulatorMagic)) != 0)
        throw Error("'" + path + "' is not a Tyndall accumulator checkpoint (bad magic)");
    in.read(reinterpret_cast<char*>(dims), sizeof(dims));
    in.read(reinterpret_cast<char*>(&passes), sizeof(passes));
    if (!in || dims[0] <= 0 || dims[1] <= 0 || dims[0] > 65536 || dims[1] > 65536)
        throw Error("'" + path + "': corrupt accumulator header");
    Accumulator acc(dims[0], dims[1]);
    acc.m_passes = passes;
    in.read(reinterpret_cast<char*>(acc.m_sum.data()), std::streamsize(acc.m_sum.size() * sizeof(double)));
    if (!in) throw Error("'" + path + "': truncated accumulator data");
    return acc;
}

}  // namespace tyndall
