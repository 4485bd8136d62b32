#include "cpu/embree_scene.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/material_eval.h"

namespace tyndall {

namespace {
const char* errorName(RTCError e) {
    switch (e) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}
void errorCallback(void*, RTCError code, const char* str) {
    std::fprintf(stderr, "tyndall: Embree error (%s): %s\n", errorName(code), str ? str : "");
}
}  // namespace

EmbreeDevice::EmbreeDevice() {
    m_device = rtcNewDevice(nullptr);
    if (!m_device) throw Error(std::string("cannot create an Embree device: ") + errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(m_device, errorCallback, nullptr);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(m_device); }

void EmbreeDevice::check(const char* what) const {
    RTCError e = rtcGetDeviceError(m_device);
    if (e != RTC_ERROR_NONE) throw Error(std::string("Embree failed while ") + what + ": " + errorName(e));
}

EmbreeScene::EmbreeScene(const Scene& scene, std::shared_ptr<EmbreeDevice> device)
    : m_scene(scene), m_device(device ? std::move(device) : std::make_shared<EmbreeDevice>()) {
    RTCDevice dev = m_device->get();
    m_rtcScene = rtcNewScene(dev);
    m_alpha.resize(scene.meshes.size());
    rtcSetSceneBuildQuality(m_rtcScene, RTC_BUILD_QUALITY_HIGH);
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const TriangleMesh& mesh = scene.meshes[m];
        RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), std::max<size_t>(mesh.positions.size(), 1)));
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            v[3 * i] = mesh.positions[i].x;
            v[3 * i + 1] = mesh.positions[i].y;
            v[3 * i + 2] = mesh.positions[i].z;
        }
        auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(uint32_t), mesh.triangleCount()));
        std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
        const bool validMaterial = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size();
        m_everySurfaceBlocks = m_everySurfaceBlocks && validMaterial &&
                               scene.materials[size_t(mesh.material)].type != MaterialType::Interface &&
                               scene.materials[size_t(mesh.material)].alphaMode == AlphaMode::Opaque;
        if (validMaterial && scene.materials[size_t(mesh.material)].alphaMode != AlphaMode::Opaque) {
            m_alpha[m] = AlphaGeometry{&scene, int(m)};
            rtcSetGeometryUserData(geom, &m_alpha[m]);
            rtcSetGeometryIntersectFilterFunction(geom, &EmbreeScene::alphaFilter);
            rtcSetGeometryOccludedFilterFunction(geom, &EmbreeScene::alphaFilter);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(m_rtcScene, geom, unsigned(m));
        rtcReleaseGeometry(geom);
    }
    m_shadingNormals.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const TriangleMesh& mesh = scene.meshes[m];
        // Shading normals only change specular, glossy and coated lobes (diffuse shading uses ng).
        if (mesh.normals.empty() || mesh.material < 0 || size_t(mesh.material) >= scene.materials.size() ||
            !scene.materials[mesh.material].usesVertexNormals())
            continue;
        std::vector<TriangleNormals>& packed = m_shadingNormals[m];
        packed.resize(mesh.triangleCount());
        for (size_t t = 0; t < packed.size(); ++t)
            for (int k = 0; k < 3; ++k) packed[t].n[k] = mesh.normals[mesh.indices[3 * t + size_t(k)]];
    }
    rtcCommitScene(m_rtcScene);
    m_device->check("building the scene BVH");
    Bounds3 b = scene.bounds;
    if (!b.empty() && length(b.diagonal()) > 0) m_sceneDiagonal = length(b.diagonal());
    m_mediumBounds = b;
}

EmbreeScene::~EmbreeScene() { rtcReleaseScene(m_rtcScene); }

void EmbreeScene::alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const AlphaGeometry*>(args->geometryUserPtr);
    const TriangleMesh& mesh = g->scene->meshes[size_t(g->mesh)];
    const Material& mat = g->scene->materials[size_t(mesh.material)];
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        const float alpha = evalSurface(*g->scene, mesh, prim, u, v, 0.0f).alpha;
        bool through;
        if (mat.alphaMode == AlphaMode::Mask) {
            through = alpha < mat.alphaCutoff;
        } else {
            // Stochastic transparency: a hash of the ray and the hit point, so a ray is a pure
            // function of what it carries (passes stay deterministic, independent of threads).
            float key[6] = {RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                            RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_z(args->ray, args->N, i), u, v};
            uint64_t h = 0x9E3779B97F4A7C15ull ^ prim;
            for (float f : key) {
                uint32_t bits;
                std::memcpy(&bits, &f, 4);
                h += bits + 0x9E3779B97F4A7C15ull;  // splitmix64 step per word
                h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
                h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
                h ^= h >> 31;
            }
            through = float(h >> 40) * (1.0f / 16777216.0f) >= alpha;
        }
        if (through) args->valid[i] = 0;
    }
}

bool EmbreeScene::intersect(const Ray& ray, SurfaceHit* hit) const {
    RTCRayHit rh;
    initRayHit(rh, ray.o, ray.d, ray.tMin, ray.tMax);
    if (!intersectRaw(rh)) return false;
    fillHit(ray, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
            Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), hit);
    return true;
}

void EmbreeScene::intersectCoherent(const Ray* rays, int n, SurfaceHit* hits, bool* found) const {
    static_assert(kPacket == 8, "rtcIntersect8");
    alignas(32) int valid[kPacket];
    alignas(32) RTCRayHit8 rh;
    for (int i = 0; i < kPacket; ++i) {
        const Ray& r = rays[std::min(i, n - 1)];
        valid[i] = i < n ? -1 : 0;
        rh.ray.org_x[i] = r.o.x, rh.ray.org_y[i] = r.o.y, rh.ray.org_z[i] = r.o.z, rh.ray.tnear[i] = r.tMin;
        rh.ray.dir_x[i] = r.d.x, rh.ray.dir_y[i] = r.d.y, rh.ray.dir_z[i] = r.d.z, rh.ray.time[i] = 0.0f;
        rh.ray.tfar[i] = r.tMax;
        rh.ray.mask[i] = 0xFFFFFFFFu;
        rh.ray.id[i] = unsigned(i);
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect8(valid, m_rtcScene, &ctx, &rh);
    for (int i = 0; i < n; ++i) {
        found[i] = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        if (found[i])
            fillHit(rays[i], rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i],
                    Vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]), &hits[i]);
    }
}

bool EmbreeScene::occluded(const Ray& ray) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = ray.o.x;
    r.org_y = ray.o.y;
    r.org_z = ray.o.z;
    r.dir_x = ray.d.x;
    r.dir_y = ray.d.y;
    r.dir_z = ray.d.z;
    r.tnear = ray.tMin;
    r.tfar = ray.tMax;
    r.mask = 0xFFFFFFFFu;
    r.flags = 0;
    r.time = 0;
    rtcOccluded1(m_rtcScene, &ctx, &r);
    return r.tfar < 0.0f;
}

MediumId EmbreeScene::mediumAt(const Vec3& p) const {
    // An irrational-looking direction avoids grazing axis-aligned walls and edges.
    Ray ray{p, normalize(Vec3(0.3187f, 0.8413f, 0.4367f))};
    SurfaceHit hit;
    for (int guard = 0; guard < 1024 && intersect(ray, &hit); ++guard) {
        const TriangleMesh& mesh = m_scene.meshes[hit.mesh];
        if (mesh.interiorMedium != mesh.exteriorMedium)
            return dot(ray.d, hit.ng) > 0 ? mesh.interiorMedium : mesh.exteriorMedium;
        ray.o = offsetOrigin(hit.p, hit.t, hit.ng, ray.d);
    }
    return m_scene.globalMedium;
}

void queryCandidates(RTCScene scene, const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found) {
    found.clear();
    if (!(sMax > 0)) return;
    CandidateQuery query;
    rtcInitIntersectContext(&query.rtc);
    query.found = &found;
    RTCRayHit rh;
    initRayHit(rh, o, d, 0.0f, sMax);
    rtcIntersect1(scene, &query.rtc, &rh);
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
}

}  // namespace tyndall
