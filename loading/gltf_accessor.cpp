#include "loading/gltf_accessor.h"

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/load_budget.h"

namespace tyndall {

void checkGltfIndex(const std::string& where, const char* kind, int64_t index, size_t count, const char* plural) {
    if (index < 0 || uint64_t(index) >= count)
        throw Error(where + ": " + kind + " index " + std::to_string(index) + " out of range (the file has " +
                    std::to_string(count) + plural + ")");
}

namespace {

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        default:
            return 0;
    }
}

double readComponent(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default:
            return 0.0;
    }
}

/// A checked window into a buffer view: element i starts at data + i * stride.
struct View {
    const unsigned char* data = nullptr;
    size_t stride = 0;
};

/// Checks that `count` elements of `elementSize` bytes at `byteOffset` fit buffer view `bv`.
View checkedView(const tinygltf::Model& model, int bv, size_t byteOffset, size_t count, size_t elementSize,
                 bool allowStride, const std::string& at) {
    checkGltfIndex(at, "bufferView", bv, model.bufferViews.size());
    const tinygltf::BufferView& view = model.bufferViews[size_t(bv)];
    std::string vat = at + ": bufferView " + std::to_string(bv);
    checkGltfIndex(vat, "buffer", view.buffer, model.buffers.size());
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
        throw Error(vat + ": bytes " + std::to_string(view.byteOffset) + ".." +
                    std::to_string(view.byteOffset + view.byteLength) + " lie outside buffer " +
                    std::to_string(view.buffer) + " ('" + buffer.name + buffer.uri.substr(0, 64) + "', " +
                    std::to_string(buffer.data.size()) + " bytes)");
    size_t stride = (allowStride && view.byteStride != 0) ? view.byteStride : elementSize;
    if (stride < elementSize)
        throw Error(vat + ": byteStride " + std::to_string(view.byteStride) + " is smaller than an element (" +
                    std::to_string(elementSize) + " bytes)");
    if (count > 0) {
        bool fits = byteOffset <= view.byteLength && elementSize <= view.byteLength - byteOffset &&
                    (count - 1) <= (view.byteLength - byteOffset - elementSize) / stride;
        if (!fits)
            throw Error(at + ": " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                        " bytes (stride " + std::to_string(stride) + ", offset " + std::to_string(byteOffset) +
                        ") do not fit bufferView " + std::to_string(bv) + " (" + std::to_string(view.byteLength) +
                        " bytes)");
    }
    return {buffer.data.data() + view.byteOffset + byteOffset, stride};
}

/// All values of an accessor as doubles (count * components), sparse substitution applied.
std::vector<double> readAccessor(const tinygltf::Model& model, int index, const std::string& where, size_t maxElements,
                                 LoadBudget* budget, int* components, int* componentType) {
    checkGltfIndex(where, "accessor", index, model.accessors.size());
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    std::string at = where + ": accessor " + std::to_string(index) + (acc.name.empty() ? "" : " '" + acc.name + "'");
    int nc = componentCount(acc.type);
    int cs = componentSize(acc.componentType);
    if (nc == 0) throw Error(at + ": type " + std::to_string(acc.type) + " is not SCALAR or VEC2..VEC4");
    if (cs == 0) throw Error(at + ": componentType " + std::to_string(acc.componentType) + " is not valid");
    if (acc.normalized && acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
        throw Error(at + ": normalized float components are not valid");
    if (acc.count > maxElements)
        throw Error(at + ": count " + std::to_string(acc.count) + " exceeds the limit of " +
                    std::to_string(maxElements) + " elements");
    *components = nc;
    *componentType = acc.componentType;
    size_t elementSize = size_t(nc) * size_t(cs);
    View v;
    if (acc.bufferView >= 0) v = checkedView(model, acc.bufferView, acc.byteOffset, acc.count, elementSize, true, at);
    if (budget) {
        // The values as doubles while reading, then as floats in the scene's mesh (an accessor
        // without a buffer view, zeros, is the one whose count no buffer bounds).
        const uint64_t values = uint64_t(acc.count) * uint64_t(nc);
        const std::string what = at + ": " + std::to_string(acc.count) + " elements of " + std::to_string(nc) +
                                 " component" + (nc > 1 ? "s" : "");
        budget->check(values * (sizeof(double) + sizeof(float)), what);
        budget->reserve(values * sizeof(float), what);
    }
    std::vector<double> out(acc.count * size_t(nc), 0.0);
    if (acc.bufferView >= 0) {
        for (size_t i = 0; i < acc.count; ++i)
            for (int c = 0; c < nc; ++c)
                out[i * nc + c] =
                    readComponent(v.data + i * v.stride + size_t(c) * cs, acc.componentType, acc.normalized);
    }
    if (acc.sparse.isSparse) {
        std::string sat = at + ": sparse";
        if (acc.sparse.count < 0 || size_t(acc.sparse.count) > acc.count)
            throw Error(sat + " count " + std::to_string(acc.sparse.count) + " is not in [0, accessor count]");
        if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
            throw Error(sat + ": negative byteOffset");
        int ict = acc.sparse.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw Error(sat + " indices: componentType " + std::to_string(ict) + " is not an unsigned integer type");
        size_t n = size_t(acc.sparse.count);
        View iv = checkedView(model, acc.sparse.indices.bufferView, size_t(acc.sparse.indices.byteOffset), n,
                              size_t(componentSize(ict)), false, sat + " indices");
        View vv = checkedView(model, acc.sparse.values.bufferView, size_t(acc.sparse.values.byteOffset), n, elementSize,
                              false, sat + " values");
        for (size_t k = 0; k < n; ++k) {
            double target = readComponent(iv.data + k * iv.stride, ict, false);
            if (target >= double(acc.count))
                throw Error(sat + " index " + std::to_string(uint64_t(target)) + " out of range (count " +
                            std::to_string(acc.count) + ")");
            for (int c = 0; c < nc; ++c)
                out[size_t(target) * nc + c] =
                    readComponent(vv.data + k * vv.stride + size_t(c) * cs, acc.componentType, acc.normalized);
        }
    }
    for (double v : out)
        if (!std::isfinite(v)) throw Error(at + ": contains a non-finite value");
    return out;
}

}  // namespace

std::vector<float> readGltfFloats(const tinygltf::Model& model, int index, int components, const std::string& where,
                                  size_t maxElements, LoadBudget* budget) {
    int nc = 0, ct = 0;
    std::vector<double> v = readAccessor(model, index, where, maxElements, budget, &nc, &ct);
    if (nc != components)
        throw Error(where + ": accessor " + std::to_string(index) + " has " + std::to_string(nc) +
                    " components per element, expected " + std::to_string(components));
    return std::vector<float>(v.begin(), v.end());
}

std::vector<uint32_t> readGltfIndices(const tinygltf::Model& model, int index, const std::string& where,
                                      size_t maxElements, LoadBudget* budget) {
    int nc = 0, ct = 0;
    std::vector<double> v = readAccessor(model, index, where, maxElements, budget, &nc, &ct);
    if (nc != 1 || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                    ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        throw Error(where + ": indices accessor " + std::to_string(index) +
                    " must be SCALAR unsigned byte, short or int");
    return std::vector<uint32_t>(v.begin(), v.end());
}

}  // namespace tyndall
