#pragma once
// Embree 3 ray queries over a Scene's triangle meshes. One Embree geometry per mesh, with the
// geometry ID equal to the mesh index. Thread-safe for concurrent queries after construction.
#include <embree3/rtcore.h>

#include <memory>

#include "core/scene.h"

namespace tyndall {

/// Owns an RTCDevice; reports Embree errors by throwing Error from the failing call's thread.
class EmbreeDevice {
public:
    EmbreeDevice();
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    RTCDevice get() const { return m_device; }
    /// Throws Error when Embree recorded an error since the last call (message names `what`).
    void check(const char* what) const;

private:
    RTCDevice m_device = nullptr;
};

struct SurfaceHit {
    float t = 0;
    int mesh = -1;
    uint32_t triangle = 0;
    Vec3 p;   ///< hit point
    Vec3 ng;  ///< unit geometric normal, pointing to the mesh exterior (CCW winding)
    Vec3 ns;  ///< unit shading normal, on ng's side: interpolated on specular meshes with normals, else ng
    float b1 = 0, b2 = 0;  ///< barycentrics of vertices 1 and 2
};

class EmbreeScene {
public:
    EmbreeScene(const Scene& scene, std::shared_ptr<EmbreeDevice> device = nullptr);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// Closest hit with t in (ray.tMin, ray.tMax).
    bool intersect(const Ray& ray, SurfaceHit* hit) const;
    /// Any hit with t in (ray.tMin, ray.tMax).
    bool occluded(const Ray& ray) const;

    /// The medium containing point `p`: found by casting a ray to the first medium-bounding surface
    /// (a mesh whose interior and exterior media differ) and reading which side it is on.
    MediumId mediumAt(const Vec3& p) const;
    /// Ray-parameter interval [t0, t1] where the global medium exists: the scene bounds, so that a
    /// ray escaping into an unbounded fog stops at the scene's edge. Returns false if none.
    bool globalMediumInterval(const Ray& ray, float* t0, float* t1) const;
    /// The stretch of o + t d, t in [0, tEnd] (tEnd: the next surface, or infinity), that lies in
    /// the medium the ray is in, as a segment with its own origin: {o + t0 d, d, 0, t1 - t0}.
    /// False when it is empty. Every stage that walks media starts here.
    bool mediumSegment(const Vec3& o, const Vec3& d, float tEnd, Ray* segment) const {
        float t0, t1;
        if (!globalMediumInterval(Ray{o, d, 0.0f, tEnd}, &t0, &t1) || !(t1 > t0)) return false;
        *segment = Ray{o + d * t0, d, 0.0f, t1 - t0};
        return true;
    }

    /// Origin for a ray leaving surface point `p` with normal `ng` in direction `d`, offset to
    /// the side `d` goes so it does not hit the surface it starts on.
    Vec3 offsetOrigin(const Vec3& p, const Vec3& ng, const Vec3& d) const {
        float eps = m_epsilon * (1.0f + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
        return p + ng * (dot(d, ng) > 0 ? eps : -eps);
    }

    const Scene& scene() const { return m_scene; }
    /// The Embree scene, for raw-throughput baselines in `tyndall bench`.
    RTCScene rtcScene() const { return m_rtcScene; }
    const std::shared_ptr<EmbreeDevice>& device() const { return m_device; }

private:
    const Scene& m_scene;
    std::shared_ptr<EmbreeDevice> m_device;
    RTCScene m_rtcScene = nullptr;
    float m_epsilon = 1e-5f;
    Bounds3 m_mediumBounds;
};

}  // namespace tyndall
