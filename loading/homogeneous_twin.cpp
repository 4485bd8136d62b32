#include "loading/homogeneous_twin.h"

#include <cmath>

#include "core/error.h"
#include "loading/mesh_builders.h"

namespace tyndall {

namespace {
Bounds3 meshBounds(const TriangleMesh& mesh) {
    Bounds3 b;
    for (const Vec3& p : mesh.positions) b.extend(p);
    return b;
}
bool overlaps(const Bounds3& a, const Bounds3& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}
bool holds(const Bounds3& outer, const Bounds3& inner) {
    return outer.contains(inner.lo) && outer.contains(inner.hi);
}
double volume(const Bounds3& b) {
    Vec3 d = b.diagonal();
    return double(d.x) * double(d.y) * double(d.z);
}

/// Confines the global grid medium `g` of `twin` to its support box (header): adds the hull, moves
/// the meshes that sat in `g` outside the box into vacuum, and returns the box (empty when the
/// support is empty or lies outside the scene). `*mean` receives the grid's mean over the box.
Bounds3 confineToSupport(Scene& twin, MediumId g, double* mean) {
    const DensityGrid& grid = *twin.media[size_t(g)].density;
    *mean = 0;
    Bounds3 box = grid.bounds();
    if (box.empty()) return box;
    for (bool grew = true; grew;) {
        grew = false;
        for (const TriangleMesh& mesh : twin.meshes) {
            const Material& mat = twin.materials[size_t(mesh.material)];
            if (mesh.exteriorMedium != g || !(mat.isTransmissive() || mat.isEmissive())) continue;
            Bounds3 mb = meshBounds(mesh);
            if (overlaps(mb, box) && !holds(box, mb)) {
                box.extend(mb);
                grew = true;
            }
        }
    }
    if (!twin.bounds.empty()) {
        const float margin = 1e-4f * length(twin.bounds.diagonal());
        box.lo = vmax(box.lo, twin.bounds.lo - Vec3(margin));
        box.hi = vmin(box.hi, twin.bounds.hi + Vec3(margin));
    }
    if (box.empty() || !(volume(box) > 0)) return Bounds3();
    const double mass = holds(box, grid.bounds()) ? grid.integratedDensity() : integrateDensity(grid, box);
    *mean = mass / volume(box);

    for (TriangleMesh& mesh : twin.meshes) {
        if (mesh.exteriorMedium != g) continue;
        const MediumId side = holds(box, meshBounds(mesh)) ? g : kVacuum;
        if (mesh.interiorMedium == g && !twin.materials[size_t(mesh.material)].isTransmissive())
            mesh.interiorMedium = side;
        mesh.exteriorMedium = side;
    }
    Material hull;
    hull.name = "homogeneous twin hull";
    hull.type = MaterialType::Interface;
    twin.materials.push_back(hull);
    TriangleMesh mesh = makeBox("homogeneous twin hull", box.lo, box.hi, int(twin.materials.size() - 1));
    mesh.interiorMedium = g;
    mesh.exteriorMedium = kVacuum;
    twin.meshes.push_back(std::move(mesh));
    twin.globalMedium = kVacuum;
    return box;
}
}  // namespace

const char* twinRegionName(TwinRegion region) {
    return region == TwinRegion::Support ? "support" : "domain";
}

TwinRegion parseTwinRegion(const std::string& text) {
    if (text == "support") return TwinRegion::Support;
    if (text == "domain") return TwinRegion::Domain;
    throw Error("twin region '" + text + "': expected 'support' (the grid's support box) or 'domain' (all space "
                "the grid's medium fills)");
}

Scene makeHomogeneousTwin(const Scene& scene, float density, std::vector<float>* used, TwinRegion region,
                          std::vector<TwinMedium>* converted) {
    Scene twin = scene;
    bool any = false;
    for (size_t i = 0; i < twin.media.size(); ++i) {
        if (twin.media[i].homogeneous()) continue;
        TwinMedium t;
        t.medium = MediumId(i);
        double mean = twin.media[i].density->meanDensity();
        if (region == TwinRegion::Support && t.medium == scene.globalMedium)
            t.box = confineToSupport(twin, t.medium, &mean);
        t.density = density >= 0 ? density : float(mean);
        Medium& m = twin.media[i];
        m.sigmaS = m.sigmaS * t.density;
        m.sigmaA = m.sigmaA * t.density;
        m.density = nullptr;
        m.name += " (homogeneous twin)";
        if (used) used->push_back(t.density);
        if (converted) converted->push_back(t);
        any = true;
    }
    if (!any) throw Error("scene '" + scene.name + "' (" + scene.source + ") has no density-grid medium to compare");
    twin.name = scene.name + "-homogeneous";
    twin.finalize();
    return twin;
}

}  // namespace tyndall
