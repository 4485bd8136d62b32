#include "loading/homogeneous_twin.h"

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
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

/// The density-weighted mean of the grid medium `m`'s Le without its emissionScale (header) over
/// `region` (empty = all space): the integral of d Le by stratified sampling (one jittered point in
/// each of kEmissionCells^3 cells over the density's bounds clipped to the region, a fixed seed)
/// over the integral of d. The constant `emission` when `m` has no emission field.
Rgb meanEmission(const Medium& m, const Bounds3& region) {
    if (!m.emissionField) return m.emission;
    const DensityGrid& grid = *m.density;
    Bounds3 b = grid.bounds();
    if (!region.empty()) {
        b.lo = vmax(b.lo, region.lo);
        b.hi = vmin(b.hi, region.hi);
    }
    if (b.empty()) return Rgb(0.0f);
    const double mass = region.empty() || holds(region, grid.bounds()) ? grid.integratedDensity()
                                                                        : integrateDensity(grid, region);
    if (!(mass > 0)) return Rgb(0.0f);
    constexpr int kEmissionCells = 96;
    const Vec3 step = b.diagonal() / float(kEmissionCells);
    Rng rng(0x7717, 24);
    double weighted[3] = {0, 0, 0};
    for (int k = 0; k < kEmissionCells; ++k)
        for (int j = 0; j < kEmissionCells; ++j)
            for (int i = 0; i < kEmissionCells; ++i) {
                const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
                const Vec3 p = b.lo + Vec3((float(i) + u) * step.x, (float(j) + v) * step.y, (float(k) + w) * step.z);
                const float d = grid.density(p);
                if (!(d > 0)) continue;
                const Rgb le = m.emissionField->radiance(p);
                for (int c = 0; c < 3; ++c) weighted[c] += double(d) * double(le[c]);
            }
    const double cell = double(step.x) * double(step.y) * double(step.z);
    return Rgb(float(weighted[0] * cell / mass), float(weighted[1] * cell / mass), float(weighted[2] * cell / mass));
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
        t.emission = meanEmission(m, t.box);
        m.sigmaS = m.sigmaS * t.density;
        m.sigmaA = m.sigmaA * t.density;
        m.density = nullptr;
        m.emissionField = nullptr;
        m.emission = t.emission;
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
