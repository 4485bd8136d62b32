// "shapes" in scene descriptions: procedural meshes built by loading/mesh_builders.h, so that the
// scene library is text without binary blobs. Keys per type are documented in
// docs/scene-format.md; every shape also takes name, material and transform.
#include <cmath>

#include "core/error.h"
#include "loading/mesh_builders.h"
#include "loading/scene_json.h"

namespace tyndall {

namespace {

int subdivisions(JsonObject& obj, int fallback) {
    return int(obj.integer("subdivisions", fallback, 0, 8));
}
size_t sphereTriangles(int s) {
    return size_t(20) << (2 * s);
}

std::vector<SurfaceWave> readWaves(const JsonValue& list, float* totalAmplitude) {
    std::vector<SurfaceWave> waves;
    *totalAmplitude = 0;
    std::vector<JsonValue> items = list.elements();
    if (items.size() > 64) list.fail("at most 64 waves");
    for (const JsonValue& v : items) {
        JsonObject w = v.object();
        SurfaceWave s;
        s.amplitude = float(w.require("amplitude").number(0.0));
        s.wavelength = float(w.require("wavelength").number(1e-6));
        JsonValue dir = w.require("direction");
        if (!dir.isArray() || dir.raw().size() != 2) dir.fail("expected [dx, dz], got " + dir.describe());
        std::vector<JsonValue> d = dir.elements();
        s.dirX = float(d[0].number());
        s.dirZ = float(d[1].number());
        if (s.dirX == 0 && s.dirZ == 0) dir.fail("expected a non-zero direction");
        s.phase = float(w.number("phase", 0.0));
        w.finish();
        *totalAmplitude += s.amplitude;
        waves.push_back(s);
    }
    return waves;
}

/// [a, b] of positive integers (grid resolutions).
void readPair(JsonObject& obj, const char* key, int fallback, int hi, int* a, int* b) {
    *a = *b = fallback;
    auto v = obj.get(key);
    if (!v) return;
    if (!v->isArray() || v->raw().size() != 2) v->fail("expected [nx, nz], got " + v->describe());
    std::vector<JsonValue> e = v->elements();
    *a = int(e[0].integer(1, hi));
    *b = int(e[1].integer(1, hi));
}

}  // namespace

Affine readTransform(JsonObject& obj) {
    Affine t;
    if (auto s = obj.get("scale")) {
        Vec3 k = s->isNumber() ? Vec3(float(s->number())) : s->vec3();
        if (k.x == 0 || k.y == 0 || k.z == 0) s->fail("scale factors must be non-zero");
        t = Affine::scaling(k.x, k.y, k.z);
    }
    if (auto r = obj.get("rotate")) {
        JsonObject rot = r->object();
        Vec3 axis = rot.require("axis").direction();
        double degrees = rot.require("degrees").number();
        rot.finish();
        t = Affine::rotationAxisAngle(axis, degrees) * t;
    }
    if (auto tr = obj.get("translate")) {
        Vec3 d = tr->vec3();
        t = Affine::translation(d.x, d.y, d.z) * t;
    }
    obj.finish();
    return t;
}

TriangleMesh readShape(JsonObject& obj, const std::string& defaultName, int material, size_t trianglesSoFar,
                       const SceneLoadOptions& options) {
    JsonValue typeValue = obj.require("type");
    std::string type = typeValue.string();
    std::string name = obj.string("name", defaultName);
    auto budget = [&](size_t n) { checkTriangleBudget(trianglesSoFar + n, options, obj.where()); };
    TriangleMesh m;
    if (type == "quad") {
        Vec3 corner = obj.require("corner").vec3();
        Vec3 e1 = obj.require("edge1").vec3(), e2 = obj.require("edge2").vec3();
        if (!(length(cross(e1, e2)) > 0)) obj.fail("edge1 and edge2 must span a parallelogram (not parallel or zero)");
        m = makeQuad(name, corner, e1, e2, material);
    } else if (type == "box") {
        Vec3 lo = obj.require("min").vec3(), hi = obj.require("max").vec3();
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) obj.fail("'min' must be below 'max' on every axis");
        m = makeBox(name, lo, hi, material, obj.boolean("inward", false));
    } else if (type == "sphere") {
        Vec3 c = obj.require("center").vec3();
        float r = float(obj.require("radius").number(1e-9));
        int s = subdivisions(obj, 4);
        budget(sphereTriangles(s));
        m = makeSphere(name, c, r, s, material);
    } else if (type == "cylinder") {
        Vec3 a = obj.require("from").vec3(), b = obj.require("to").vec3();
        if (!(length(b - a) > 0)) obj.fail("'from' and 'to' must differ");
        float r = float(obj.require("radius").number(1e-9));
        m = makeCylinder(name, a, b, r, int(obj.integer("segments", 32, 3, 4096)), material);
    } else if (type == "bumpy_sphere") {
        Vec3 c = obj.require("center").vec3();
        float r = float(obj.require("radius").number(1e-9));
        int s = subdivisions(obj, 5);
        float amplitude = float(obj.number("amplitude", 0.05, 0.0, 0.9));
        float frequency = float(obj.number("frequency", 8.0, 0.0, 1000.0));
        int bumps = int(obj.integer("bumps", 12, 0, 256));
        uint32_t seed = uint32_t(obj.integer("seed", 1, 0, 0xffffffffll));
        budget(sphereTriangles(s));
        m = makeBumpySphere(name, c, r, s, amplitude, frequency, bumps, seed, material);
    } else if (type == "water") {
        Vec3 top = obj.require("top").vec3();
        JsonValue sizeValue = obj.require("size");
        if (!sizeValue.isArray() || sizeValue.raw().size() != 2)
            sizeValue.fail("expected [sx, sz], got " + sizeValue.describe());
        std::vector<JsonValue> size = sizeValue.elements();
        float sx = float(size[0].number(1e-6)), sz = float(size[1].number(1e-6));
        float depth = float(obj.require("depth").number(1e-6));
        int rx, rz;
        readPair(obj, "resolution", 64, 2048, &rx, &rz);
        float amplitude = 0;
        std::vector<SurfaceWave> waves;
        if (auto w = obj.get("waves")) waves = readWaves(*w, &amplitude);
        if (amplitude >= depth)
            obj.fail("the waves' amplitudes add up to more than 'depth': the surface would cross the bottom");
        budget(size_t(4) * size_t(rx) * size_t(rz) + size_t(4) * size_t(rx + rz));
        m = makeWaterVolume(name, top, sx, sz, depth, rx, rz, waves, material);
    } else if (type == "paraboloid") {
        Vec3 apex = obj.require("apex").vec3();
        Vec3 axis = obj.require("axis").direction();
        float f = float(obj.require("focal_length").number(1e-6));
        float outer = float(obj.require("radius").number(1e-6));
        float inner = float(obj.number("inner_radius", 0.0, 0.0));
        if (inner >= outer) obj.fail("inner_radius must be smaller than radius");
        int rings = int(obj.integer("rings", 16, 1, 1024)), segments = int(obj.integer("segments", 48, 3, 4096));
        budget(size_t(2) * size_t(rings) * size_t(segments));
        m = makeParaboloid(name, apex, axis, f, inner, outer, rings, segments, material);
    } else if (type == "lens") {
        Vec3 c = obj.require("center").vec3();
        Vec3 axis = obj.require("axis").direction();
        float r = float(obj.require("radius").number(1e-6));
        float t = float(obj.require("thickness").number(1e-6));
        float rc = float(obj.require("curvature_radius").number(1e-6));
        if (rc < r) obj.fail("curvature_radius must be at least the aperture radius");
        float sag = rc - std::sqrt(rc * rc - r * r);
        if (t < 2.0f * sag)
            obj.fail("thickness is less than the two caps' sagitta (" + std::to_string(2.0f * sag) +
                     "): the caps would cross");
        int rings = int(obj.integer("rings", 8, 1, 1024)), segments = int(obj.integer("segments", 48, 3, 4096));
        budget(size_t(6) * size_t(rings) * size_t(segments));
        m = makeLens(name, c, axis, r, t, rc, rings, segments, material);
    } else if (type == "perforated_sphere") {
        Vec3 c = obj.require("center").vec3();
        float r = float(obj.require("radius").number(1e-9));
        int s = subdivisions(obj, 3);
        int holes = int(obj.integer("holes", 24, 0, 10000));
        float holeAngle = float(obj.number("hole_angle", 6.0, 0.0, 90.0) * kRadiansPerDegree);
        budget(sphereTriangles(s));
        m = makePerforatedSphere(name, c, r, s, holes, holeAngle, material);
    } else if (type == "mesh") {
        std::vector<JsonValue> pos = obj.require("positions").elements();
        std::vector<JsonValue> idx = obj.require("indices").elements();
        if (idx.size() % 3 != 0) obj.fail("'indices' must hold 3 per triangle, got " + std::to_string(idx.size()));
        budget(idx.size() / 3);
        m.name = name;
        m.material = material;
        for (const JsonValue& p : pos) m.positions.push_back(p.vec3());
        for (const JsonValue& i : idx) {
            if (pos.empty()) i.fail("index into an empty 'positions'");
            m.indices.push_back(uint32_t(i.integer(0, int64_t(pos.size()) - 1)));
        }
        if (auto normals = obj.get("normals")) {
            std::vector<JsonValue> n = normals->elements();
            if (n.size() != pos.size()) normals->fail("expected one normal per position");
            for (const JsonValue& v : n) m.normals.push_back(normalize(v.direction()));
        }
    } else {
        typeValue.fail(
            "expected a shape type (quad, box, sphere, cylinder, bumpy_sphere, water, paraboloid, lens, "
            "perforated_sphere, mesh), got " +
            typeValue.describe());
    }
    if (auto t = obj.get("transform")) {
        JsonObject tobj = t->object();
        transformMesh(m, readTransform(tobj));
    }
    obj.finish();
    return m;
}

}  // namespace tyndall
