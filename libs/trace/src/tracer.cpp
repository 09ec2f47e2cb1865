// The path tracer (fresnel/trace/tracer.h). Long (~720 lines) because the Embree scene (geometry,
// instancing of the flattened meshes, alpha filters), the path loop with its next-event estimation
// and the tiled, progressive image loop are one concern: a path and the scene it is traced in.
#include "fresnel/trace/tracer.h"

#include "splitmix.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/parallel.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/trace/area_lights.h"
#include "fresnel/ibl/precompute.h"
#include "fresnel/material/bsdf.h"
#include "fresnel/material/sampling.h"
#include "fresnel/scene/scene_textures.h"

namespace fresnel::trace {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// ---------------------------------------------------------------------------
// Random numbers: PCG32 (O'Neill), its state hashed from (seed, pixel, sample).

struct Rng {
    std::uint64_t state = 0, inc = 1;
    Rng(std::uint64_t seed, std::uint64_t stream) {
        inc = (stream << 1u) | 1u;
        next();
        state += seed;
        next();
    }
    std::uint32_t next() {
        std::uint64_t old = state;
        state = old * 6364136223846793005ull + inc;
        auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    float uniform() { return float(next() >> 8) * 0x1p-24f; }  // [0, 1)
    glm::vec2 uniform2() {
        float a = uniform();
        return {a, uniform()};
    }
    glm::vec3 uniform3() {
        float a = uniform(), b = uniform();
        return {a, b, uniform()};
    }
};


// Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
// Gems, 2019): the ray origin moved off the surface along `n` by a few ulps of its position.
glm::vec3 offset_ray(glm::vec3 p, glm::vec3 n) {
    constexpr float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        int of = int(kIntScale * n[i]);
        std::int32_t bits;
        std::memcpy(&bits, &p[i], 4);
        bits += p[i] < 0 ? -of : of;
        float pi;
        std::memcpy(&pi, &bits, 4);
        out[i] = std::fabs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
    }
    return out;
}

// Textures (fresnel::SceneTextures): every (texture, colour space) a material reads, decoded
// once with its mip chain. Camera rays read level 0 (the pixel's samples integrate its
// footprint, as Cycles does); later bounces read level kSecondaryLod, a footprint that a
// diffuse or glossy bounce far exceeds anyway, and one that stays in the caches (incoherent
// reads of five 2048^2 maps were a quarter of the time).

// One primitive's triangles and vertex attributes: in world space for a mesh placed once, in
// the mesh's own space for a mesh placed several times (a prototype that Embree instances; its
// placements: Placement).
struct Geometry {
    const Material* material = nullptr;
    int material_index = -1;  // the scene's material (-1: the default material)
    int node = -1;            // the scene node it is an instance of
    const TextureSource* textures = nullptr;
    std::vector<glm::vec3> positions, normals, bitangents;
    std::vector<glm::vec4> tangents;  // xyz world, w the handedness (mirrors included)
    std::vector<glm::vec2> uv0, uv1;
    std::vector<glm::vec4> colors;
    std::vector<std::uint32_t> indices;  // 3 per triangle
    bool mirrored = false;               // det(world) < 0: clockwise triangles face front (prototypes: never)
    VertexInputs inputs;
    bool filtered = false;  // single-sided or not opaque: hits go through filter_hits

    SurfacePoint surface_point(unsigned prim, float u, float v) const {
        const std::uint32_t* t = &indices[std::size_t(prim) * 3];
        float w0 = 1.0f - u - v;
        SurfacePoint sp;
        sp.inputs = inputs;
        sp.lod = 0.0f;
        if (!uv0.empty()) sp.uv0 = w0 * uv0[t[0]] + u * uv0[t[1]] + v * uv0[t[2]];
        if (!uv1.empty()) sp.uv1 = w0 * uv1[t[0]] + u * uv1[t[1]] + v * uv1[t[2]];
        if (!colors.empty()) sp.color = w0 * colors[t[0]] + u * colors[t[1]] + v * colors[t[2]];
        return sp;
    }
};

const Material kDefaultMaterial{};
constexpr float kSecondaryLod = 3.0f;  // 2048^2 -> 256^2

// The per-query context: Embree's, and the random seed of the ray for stochastic opacity.
// The seeds are per ray of a packet, found by the ray's id (single rays: id 0).
struct RayContext {
    RTCIntersectContext rtc;
    std::uint64_t seed[8] = {};
};

// Rejects hits on back faces of single-sided materials, on MASK texels below the cutoff, and
// on BLEND surfaces with probability 1 - alpha (a hash of the ray's seed and the triangle,
// so that the decision is the same whichever order Embree reports candidates in).
void filter_hits(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
    const auto* ctx = reinterpret_cast<const RayContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                      RTCRayN_dir_z(args->ray, args->N, i));
        // Embree's Ng is the counter-clockwise normal cross(v1 - v0, v2 - v0), unnormalised.
        glm::vec3 ng(RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                     RTCHitN_Ng_z(args->hit, args->N, i));
        bool back = (glm::dot(ng, dir) > 0.0f) != g->mirrored;
        const Material& m = *g->material;
        if (back && !m.double_sided) {
            args->valid[i] = 0;
            continue;
        }
        if (m.alpha_mode == AlphaMode::Opaque) continue;
        SurfacePoint sp = g->surface_point(prim, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
        EvaluatedMaterial em = evaluate(m, *g->textures, sp);
        if (em.discard) {
            args->valid[i] = 0;
        } else if (m.alpha_mode == AlphaMode::Blend) {
            std::uint64_t seed = ctx->seed[RTCRayN_id(args->ray, args->N, i) & 7u];
            std::uint64_t geom = RTCHitN_geomID(args->hit, args->N, i);
            const unsigned inst = RTCHitN_instID(args->hit, args->N, i, 0);
            if (inst != RTC_INVALID_GEOMETRY_ID) geom = splitmix64(geom ^ (std::uint64_t(inst) << 32));  // a placement's own
            std::uint64_t h = splitmix64(seed ^ splitmix64((geom << 32) | prim));
            float u = float(h >> 40) * 0x1p-24f;
            if (u >= em.alpha) args->valid[i] = 0;
        }
    }
}

// One placement of a prototype (a mesh placed by several nodes): an Embree instance of the
// prototype's scene. The hit's attributes are in the mesh's space; these take them to world space.
struct Placement {
    glm::mat4 world{1.0f};
    glm::mat3 linear{1.0f}, normal_matrix{1.0f};
    float handedness = 1.0f;  // sign of det(world): mirrors flip the bitangent
    int node = -1;
    const std::vector<std::unique_ptr<Geometry>>* geometries = nullptr;  // the prototype's, by geometry id
};

// The surface a hit lands on, in world space (Impl::surface): the geometry's material and
// textures, the point, the geometric normal facing the front side (counter-clockwise, or
// clockwise under a mirroring transform), the interpolated shading normal and, with tangents,
// the tangent frame; the material inputs at the point (SurfacePoint, frame not yet set).
struct SurfaceHit {
    const Geometry* geometry = nullptr;
    int node = -1;
    glm::vec3 p{0.0f}, ng{0.0f, 0.0f, 1.0f}, ns{0.0f, 0.0f, 1.0f};
    glm::vec3 tangent{1.0f, 0.0f, 0.0f}, bitangent{0.0f, 1.0f, 0.0f};
    SurfacePoint sp;
};

struct Hit {
    unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = 0;
    unsigned inst = RTC_INVALID_GEOMETRY_ID;  // the placement (Impl::placements) when a prototype was hit
    float t = 0, u = 0, v = 0;
    glm::vec3 ng{0.0f};  // Embree's: counter-clockwise, unnormalised
    bool valid() const { return geom != RTC_INVALID_GEOMETRY_ID; }
};

}  // namespace

struct TraceScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::unique_ptr<SceneTextures> textures;
    std::vector<Material> materials;  // the scene's, occlusion maps removed
    std::vector<std::unique_ptr<Geometry>> geometries;  // by Embree geometry id (the top-level scene's)
    // Meshes placed several times: each prototype's scene and geometries, and every placement
    // by its instance's geometry id in the top-level scene (none there: an empty entry).
    std::vector<RTCScene> prototype_scenes;
    std::vector<std::unique_ptr<std::vector<std::unique_ptr<Geometry>>>> prototypes;
    std::vector<Placement> placements;
    std::size_t triangles = 0;
    std::size_t stored_triangles = 0;  // held once per prototype
    double build_ms = 0;

    // One primitive's triangles at `world` (the identity: a prototype, in the mesh's own
    // space), or nothing when it has none to trace.
    std::unique_ptr<Geometry> make_geometry(const Primitive& prim, const glm::mat4& world, int node) const {
        if (prim.topology != Topology::Triangles || prim.positions.empty()) return nullptr;
        const glm::mat3 linear(world);
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
        const float det = glm::determinant(linear);
        auto g = std::make_unique<Geometry>();
        const bool own = prim.material >= 0 && prim.material < int(materials.size());
        g->material = own ? &materials[std::size_t(prim.material)] : &kDefaultMaterial;
        g->material_index = own ? prim.material : -1;
        g->node = node;
        g->textures = textures.get();
        g->mirrored = det < 0.0f;
        const std::size_t n = prim.positions.size();
        g->positions.resize(n);
        for (std::size_t i = 0; i < n; ++i) g->positions[i] = glm::vec3(world * glm::vec4(prim.positions[i], 1.0f));
        if (prim.normals.size() == n) {
            g->normals.resize(n);
            for (std::size_t i = 0; i < n; ++i) g->normals[i] = unit_or(normal_matrix * prim.normals[i], glm::vec3(0, 0, 1));
        }
        g->inputs.has_uv0 = prim.uv0.size() == n;
        g->inputs.has_uv1 = prim.uv1.size() == n;
        g->inputs.has_tangent = prim.tangents.size() == n && !g->normals.empty();
        if (g->inputs.has_tangent) {
            g->tangents.resize(n);
            g->bitangents.resize(n);
            const float handedness = det < 0.0f ? -1.0f : 1.0f;
            for (std::size_t i = 0; i < n; ++i) {
                const glm::vec3 t = unit_or(linear * glm::vec3(prim.tangents[i]), glm::vec3(1, 0, 0));
                const float w = prim.tangents[i].w * handedness;
                g->tangents[i] = glm::vec4(t, w);
                g->bitangents[i] = glm::cross(g->normals[i], t) * w;
            }
        }
        if (g->inputs.has_uv0) g->uv0 = prim.uv0;
        if (g->inputs.has_uv1) g->uv1 = prim.uv1;
        if (prim.colors.size() == n) g->colors = prim.colors;
        if (prim.indices.empty()) {
            g->indices.resize(n / 3 * 3);
            for (std::size_t i = 0; i < g->indices.size(); ++i) g->indices[i] = std::uint32_t(i);
        } else {
            g->indices.reserve(prim.indices.size() / 3 * 3);
            for (std::size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
                const std::uint32_t a = prim.indices[i], b = prim.indices[i + 1], c = prim.indices[i + 2];
                if (a >= n || b >= n || c >= n) continue;
                g->indices.insert(g->indices.end(), {a, b, c});
            }
        }
        if (g->indices.empty()) return nullptr;
        g->filtered = !g->material->double_sided || g->material->alpha_mode != AlphaMode::Opaque;
        return g;
    }
    // Attaches `g`'s triangles to `target` (the top-level scene or a prototype's) and keeps it
    // in `table` under its geometry id.
    void attach(RTCScene target, std::unique_ptr<Geometry> g, std::vector<std::unique_ptr<Geometry>>& table) const {
        const std::size_t n = g->positions.size(), tris = g->indices.size() / 3;
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
        for (std::size_t i = 0; i < n; ++i) std::copy_n(&g->positions[i].x, 3, vb + i * 3);
        auto* ib = static_cast<std::uint32_t*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), tris));
        std::copy(g->indices.begin(), g->indices.end(), ib);
        rtcSetGeometryUserData(geom, g.get());
        if (g->filtered) {
            rtcSetGeometryIntersectFilterFunction(geom, filter_hits);
            rtcSetGeometryOccludedFilterFunction(geom, filter_hits);
        }
        rtcCommitGeometry(geom);
        const unsigned id = rtcAttachGeometry(target, geom);
        rtcReleaseGeometry(geom);
        if (id >= table.size()) table.resize(id + 1);
        table[id] = std::move(g);
    }

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        for (RTCScene p : prototype_scenes) rtcReleaseScene(p);
        if (device) rtcReleaseDevice(device);
    }

    Hit intersect(glm::vec3 o, glm::vec3 d, float tfar, std::uint64_t seed, bool coherent = false) const {
        RayContext ctx;
        rtcInitIntersectContext(&ctx.rtc);
        if (coherent) ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        ctx.seed[0] = seed;
        RTCRayHit rh;
        rh.ray.org_x = o.x;
        rh.ray.org_y = o.y;
        rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = tfar;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx.rtc, &rh);
        Hit h;
        h.geom = rh.hit.geomID;
        h.inst = rh.hit.instID[0];
        h.prim = rh.hit.primID;
        h.t = rh.ray.tfar;
        h.u = rh.hit.u;
        h.v = rh.hit.v;
        h.ng = glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        return h;
    }

    // Eight camera rays at once (Embree's packet traversal is much faster for coherent rays);
    // lanes with active[i] == 0 are skipped.
    void intersect8(const int active[8], const glm::vec3 o[8], const glm::vec3 d[8], const std::uint64_t seeds[8],
                    Hit hits[8]) const {
        RayContext ctx;
        rtcInitIntersectContext(&ctx.rtc);
        ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(32) int valid[8];
        alignas(32) RTCRayHit8 rh;
        for (int i = 0; i < 8; ++i) {
            valid[i] = active[i] ? -1 : 0;
            ctx.seed[i] = seeds[i];
            rh.ray.org_x[i] = o[i].x;
            rh.ray.org_y[i] = o[i].y;
            rh.ray.org_z[i] = o[i].z;
            rh.ray.dir_x[i] = d[i].x;
            rh.ray.dir_y[i] = d[i].y;
            rh.ray.dir_z[i] = d[i].z;
            rh.ray.tnear[i] = 0.0f;
            rh.ray.tfar[i] = INFINITY;
            rh.ray.time[i] = 0.0f;
            rh.ray.mask[i] = 0xFFFFFFFFu;
            rh.ray.id[i] = unsigned(i);
            rh.ray.flags[i] = 0;
            rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, scene, &ctx.rtc, &rh);
        for (int i = 0; i < 8; ++i) {
            Hit& h = hits[i];
            h.geom = rh.hit.geomID[i];
            h.inst = rh.hit.instID[0][i];
            h.prim = rh.hit.primID[i];
            h.t = rh.ray.tfar[i];
            h.u = rh.hit.u[i];
            h.v = rh.hit.v[i];
            h.ng = glm::vec3(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
        }
    }

    // The surface `hit` (valid) lands on, in world space. A prototype's attributes are taken
    // there per vertex as the world-space build stores them (normals and tangents normalised,
    // the bitangent from the world-space normal and tangent), then interpolated alike.
    SurfaceHit surface(const Hit& hit) const {
        SurfaceHit s;
        const Placement* pl = hit.inst != RTC_INVALID_GEOMETRY_ID ? &placements[hit.inst] : nullptr;
        const Geometry& g = pl ? *(*pl->geometries)[hit.geom] : *geometries[hit.geom];
        s.geometry = &g;
        s.node = pl ? pl->node : g.node;
        const std::uint32_t* tri = &g.indices[std::size_t(hit.prim) * 3];
        const float u = hit.u, v = hit.v, w0 = 1.0f - u - v;
        const glm::vec3 p = w0 * g.positions[tri[0]] + u * g.positions[tri[1]] + v * g.positions[tri[2]];
        s.p = pl ? glm::vec3(pl->world * glm::vec4(p, 1.0f)) : p;
        const glm::vec3 ng = g.mirrored ? -hit.ng : hit.ng;  // Embree's: counter-clockwise, in the geometry's space
        s.ng = glm::normalize(pl ? pl->normal_matrix * ng : ng);
        s.sp = g.surface_point(hit.prim, u, v);
        s.ns = s.ng;
        glm::vec3 n[3], t[3], b[3];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = tri[k];
            if (!g.normals.empty()) n[k] = pl ? unit_or(pl->normal_matrix * g.normals[i], glm::vec3(0, 0, 1)) : g.normals[i];
            if (!g.inputs.has_tangent) continue;
            if (pl) {
                t[k] = unit_or(pl->linear * glm::vec3(g.tangents[i]), glm::vec3(1, 0, 0));
                b[k] = glm::cross(n[k], t[k]) * (g.tangents[i].w * pl->handedness);
            } else {
                t[k] = glm::vec3(g.tangents[i]);
                b[k] = g.bitangents[i];
            }
        }
        if (!g.normals.empty()) s.ns = unit_or(w0 * n[0] + u * n[1] + v * n[2], s.ng);
        if (g.inputs.has_tangent) {
            s.tangent = unit_or(w0 * t[0] + u * t[1] + v * t[2], glm::vec3(1, 0, 0));
            s.bitangent = unit_or(w0 * b[0] + u * b[1] + v * b[2], glm::vec3(0, 1, 0));
        }
        return s;
    }
    static glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
        const float len = glm::length(v);
        return len > 0 ? v / len : fallback;
    }

    bool occluded(glm::vec3 o, glm::vec3 d, float tfar, std::uint64_t seed) const {
        RayContext ctx;
        rtcInitIntersectContext(&ctx.rtc);
        ctx.seed[0] = seed;
        RTCRay r;
        r.org_x = o.x;
        r.org_y = o.y;
        r.org_z = o.z;
        r.dir_x = d.x;
        r.dir_y = d.y;
        r.dir_z = d.z;
        r.tnear = 0.0f;
        r.tfar = tfar;
        r.time = 0.0f;
        r.mask = 0xFFFFFFFFu;
        r.id = 0;
        r.flags = 0;
        rtcOccluded1(scene, &ctx.rtc, &r);
        return r.tfar < 0.0f;
    }
};

TraceScene::TraceScene(const Scene& scene, const std::vector<NodeInstance>& instances, const TraceSceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
    auto t0 = Clock::now();
    Impl& im = *impl_;
    im.device = rtcNewDevice(nullptr);
    if (!im.device) throw Error("embree", "", "rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    im.scene = rtcNewScene(im.device);
    rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);
    im.textures = std::make_unique<SceneTextures>(scene);
    // The materials without their occlusion maps: the tracer computes occlusion, and a map
    // read for nothing costs a texture fetch per hit.
    im.materials = scene.materials;
    for (Material& m : im.materials) m.occlusion = TextureSlot{};

    // A mesh that several visible nodes place (EXT_mesh_gpu_instancing's instances, repeated
    // parts, a scene file's copies) is built once in its own space and placed by Embree
    // instances (options.instancing); every other one is built in world space.
    std::vector<int> placements(scene.meshes.size(), 0);
    auto placed = [&](const NodeInstance& inst) {  // the node's mesh, or -1 when it places none
        const Node& node = scene.nodes[std::size_t(inst.node)];
        return node.mesh < 0 || node.mesh >= int(scene.meshes.size()) || !inst.visible ? -1 : node.mesh;
    };
    for (const NodeInstance& inst : instances)
        if (const int mesh = placed(inst); mesh >= 0 && !scene.nodes[std::size_t(inst.node)].world_space_mesh)
            ++placements[std::size_t(mesh)];
    // Per mesh placed several times: its prototype's geometries and triangles (built on first use).
    std::vector<std::vector<std::unique_ptr<Geometry>>*> prototype_of(scene.meshes.size(), nullptr);
    std::vector<RTCScene> prototype_scene_of(scene.meshes.size(), nullptr);
    std::vector<std::size_t> prototype_triangles(scene.meshes.size(), 0);
    for (const NodeInstance& inst : instances) {
        const int mesh = placed(inst);
        if (mesh < 0) continue;
        const std::vector<Primitive>& prims = scene.meshes[std::size_t(mesh)].primitives;
        const bool world_space = scene.nodes[std::size_t(inst.node)].world_space_mesh;
        if (world_space || !options.instancing || placements[std::size_t(mesh)] < 2) {
            for (const Primitive& prim : prims)
                if (auto g = im.make_geometry(prim, world_space ? glm::mat4(1.0f) : inst.world, inst.node)) {
                    im.triangles += g->indices.size() / 3;
                    im.stored_triangles += g->indices.size() / 3;
                    im.attach(im.scene, std::move(g), im.geometries);
                }
            continue;
        }
        if (!prototype_of[std::size_t(mesh)]) {
            RTCScene prototype = rtcNewScene(im.device);
            rtcSetSceneBuildQuality(prototype, RTC_BUILD_QUALITY_HIGH);
            im.prototype_scenes.push_back(prototype);
            im.prototypes.push_back(std::make_unique<std::vector<std::unique_ptr<Geometry>>>());
            prototype_of[std::size_t(mesh)] = im.prototypes.back().get();
            prototype_scene_of[std::size_t(mesh)] = prototype;
            for (const Primitive& prim : prims)
                if (auto g = im.make_geometry(prim, glm::mat4(1.0f), -1)) {
                    prototype_triangles[std::size_t(mesh)] += g->indices.size() / 3;
                    im.attach(prototype, std::move(g), *prototype_of[std::size_t(mesh)]);
                }
            rtcCommitScene(prototype);
            im.stored_triangles += prototype_triangles[std::size_t(mesh)];
        }
        if (prototype_triangles[std::size_t(mesh)] == 0) continue;
        RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, prototype_scene_of[std::size_t(mesh)]);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.world[0][0]);
        rtcCommitGeometry(geom);
        const unsigned id = rtcAttachGeometry(im.scene, geom);
        rtcReleaseGeometry(geom);
        if (id >= im.placements.size()) im.placements.resize(id + 1);
        Placement& pl = im.placements[id];
        pl.world = inst.world;
        pl.linear = glm::mat3(inst.world);
        pl.normal_matrix = glm::transpose(glm::inverse(pl.linear));
        pl.handedness = glm::determinant(pl.linear) < 0.0f ? -1.0f : 1.0f;
        pl.node = inst.node;
        pl.geometries = prototype_of[std::size_t(mesh)];
        im.triangles += prototype_triangles[std::size_t(mesh)];
    }
    rtcCommitScene(im.scene);
    RTCError err = rtcGetDeviceError(im.device);
    if (err != RTC_ERROR_NONE) throw Error("embree", "", "building the scene failed (error " + std::to_string(int(err)) + ")");
    im.build_ms = ms_since(t0);
}

TraceScene::~TraceScene() = default;
std::size_t TraceScene::triangle_count() const { return impl_->triangles; }
std::size_t TraceScene::stored_triangle_count() const { return impl_->stored_triangles; }
std::size_t TraceScene::placement_count() const { return impl_->placements.size() - std::size_t(std::count_if(
    impl_->placements.begin(), impl_->placements.end(), [](const Placement& p) { return p.geometries == nullptr; })); }
double TraceScene::build_ms() const { return impl_->build_ms; }
bool TraceScene::occluded(glm::vec3 p, glm::vec3 n, glm::vec3 d, float tfar, std::uint64_t seed) const {
    return impl_->occluded(offset_ray(p, n), d, tfar, seed);
}

namespace {

struct Integrator {
    const TraceScene::Impl& scene;
    const std::vector<LightInstance>& lights;
    const EnvironmentLight* env;
    const TraceSettings& settings;
    std::uint64_t rays = 0;
    const bool has_area_lights = std::any_of(lights.begin(), lights.end(), [](const LightInstance& l) { return l.is_area(); });

    static float power_heuristic(float a, float b) {
        float a2 = a * a, b2 = b * b;
        return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
    }

    // The radiance along one camera ray; `covered` says whether it hit the scene. `first`,
    // when given, is the camera ray's hit, already traced (in a packet) with the seed that
    // this function would have drawn from `rng` first.
    glm::vec3 radiance(glm::vec3 origin, glm::vec3 dir, Rng& rng, bool& covered, const Hit* first = nullptr) {
        glm::vec3 L(0.0f), beta(1.0f);
        float bsdf_pdf = 0.0f;  // of the direction that led here (for MIS with the environment)
        bool env_counted = false;  // no-env-visibility: the last vertex already took the environment
        bool transmitted = false;  // the last bounce went through a transmissive surface (no NEE there)
        covered = false;
        for (int bounce = 0;; ++bounce) {
            ++rays;
            Hit hit = bounce == 0 && first ? *first : scene.intersect(origin, dir, INFINITY, splitmix64(rng.next()), bounce == 0);
            if (!hit.valid()) {
                if (bounce == 0) {
                    if (env && settings.env_background)
                        L += settings.background_cube
                                 ? settings.background_cube->sample(env->to_environment(dir), settings.background_lod) *
                                       env->intensity()
                                 : env->radiance(dir);
                } else if (env && !env_counted) {
                    L += beta * env->radiance(dir) * (transmitted ? 1.0f : power_heuristic(bsdf_pdf, env->pdf(dir)));
                }
            }
            // Area lights the ray met before the surface (they block nothing): the BSDF-sampled
            // half of their multiple importance sampling (all of it after a transmission, where no
            // light was sampled). Camera rays do not see them.
            if (bounce > 0 && has_area_lights) {
                const float tmax = hit.valid() ? hit.t : INFINITY;
                for (const LightInstance& light : lights) {
                    if (!light.is_area()) continue;
                    float light_pdf = 0.0f, t = 0.0f;
                    glm::vec3 le = area_light_hit(light, origin, dir, tmax, light_pdf, t);
                    if (light_pdf > 0.0f) L += beta * le * (transmitted ? 1.0f : power_heuristic(bsdf_pdf, light_pdf));
                }
            }
            if (!hit.valid()) break;
            if (bounce == 0) covered = true;
            const SurfaceHit sh = scene.surface(hit);
            const Geometry& g = *sh.geometry;
            glm::vec3 p = sh.p;
            glm::vec3 ng = sh.ng;
            glm::vec3 wo = -dir;
            bool back = glm::dot(ng, wo) < 0.0f;
            SurfacePoint sp = sh.sp;
            if (bounce > 0) sp.lod = kSecondaryLod;
            glm::vec3 ns = sh.ns;
            if (g.inputs.has_tangent) {
                sp.tangent = sh.tangent;
                sp.bitangent = sh.bitangent;
            }
            if (back) {  // double-sided back face: the flipped frame (pbr.frag's shading_frame)
                ng = -ng;
                ns = -ns;
                sp.tangent = -sp.tangent;
                sp.bitangent = -sp.bitangent;
            }
            sp.normal = ns;
            EvaluatedMaterial m = evaluate(*g.material, *g.textures, sp);
            if (m.unlit) {
                L += beta * m.surface.base_color;
                break;
            }
            L += beta * m.emissive;
            if (bounce >= settings.max_bounces) break;

            // Shading normals that face away from the viewer (normal maps, smoothed normals)
            // are bent back just above the horizon, so that the BRDF's frame stays valid.
            auto face_viewer = [&](glm::vec3 n) {
                float d = glm::dot(n, wo);
                if (d >= 1e-3f) return n;
                return glm::normalize(n + (1e-3f - d) * wo);
            };
            m.normal = face_viewer(m.normal);
            m.clearcoat_normal = face_viewer(m.clearcoat_normal);
            m.surface.perceptual_roughness = std::max(m.surface.perceptual_roughness, kMinSampledRoughness);
            m.clearcoat_roughness = std::max(m.clearcoat_roughness, kMinSampledRoughness);

            EnergyCompensation comp;
            if (settings.brdf_lut) {
                const float e = ibl::sample_brdf_lut(*settings.brdf_lut, std::max(glm::dot(m.normal, wo), 0.0f),
                                                     m.surface.perceptual_roughness).z;
                comp = energy_compensation(m, e);
            }
            const Bsdf bsdf(m, wo, settings.brdf, comp);
            // Next-event estimation: every punctual light, then one sample of the environment.
            glm::vec3 p_out = offset_ray(p, ng);
            for (const LightInstance& light : lights) {
                if (light.is_area()) {
                    // A point on the light, weighed against the BSDF's sampling of the same direction.
                    AreaLightSample as = sample_area_light(light, p, rng.uniform2());
                    if (!(as.pdf > 0.0f)) continue;
                    const bool behind = glm::dot(as.l, ng) <= 0.0f;
                    if (behind && !(m.diffuse_transmission > 0.0f)) continue;
                    glm::vec3 f = bsdf.eval(as.l) * as.radiance;
                    if (!(f.x + f.y + f.z > 0.0f)) continue;
                    ++rays;
                    if (!scene.occluded(behind ? offset_ray(p, -ng) : p_out, as.l, as.distance * (1.0f - 1e-4f),
                                        splitmix64(rng.next())))
                        L += beta * f * (power_heuristic(as.pdf, bsdf.pdf(as.l)) / as.pdf);
                    continue;
                }
                glm::vec3 l;
                float dist = 0;
                glm::vec3 li = light_incident(light, p, l, dist);
                // KHR_materials_diffuse_transmission: lights behind the surface light its transmitted lobe.
                const bool behind = glm::dot(l, ng) <= 0.0f;
                if (li.x + li.y + li.z <= 0.0f || (behind && !(m.diffuse_transmission > 0.0f))) continue;
                glm::vec3 f = bsdf.eval(l) * li;  // the BSDF the path samples (with transmission, less its share of the diffuse)
                if (f.x + f.y + f.z <= 0.0f) continue;
                ++rays;
                float tmax = std::isfinite(dist) ? dist * (1.0f - 1e-4f) : INFINITY;
                // A light with a size shades as the point or direction it is and casts the
                // shadow of its extent (the rasteriser's contact-hardening shadows): a point or
                // spot light's shadow ray goes to a uniform point of its bulb's disk as seen from
                // here, a directional light's along a uniform direction of its cone.
                glm::vec3 shadow_dir = l;
                if (light.radius > 0.0f) {
                    const glm::vec2 u = rng.uniform2();
                    glm::vec3 t, b;
                    sampling::basis(l, t, b);
                    const float phi = 6.28318531f * u.y;
                    const glm::vec3 across = std::cos(phi) * t + std::sin(phi) * b;
                    if (light.type == Light::Type::Directional) {
                        const float cos_t = 1.0f - u.x * (1.0f - std::cos(std::min(light.radius, 0.5f)));
                        shadow_dir = cos_t * l + std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t)) * across;
                    } else if (std::isfinite(dist)) {
                        const glm::vec3 target = l * dist + light.radius * std::sqrt(u.x) * across;
                        const float target_dist = glm::length(target);
                        shadow_dir = target / target_dist;
                        tmax = target_dist * (1.0f - 1e-4f);
                    }
                }
                if (!scene.occluded(behind ? offset_ray(p, -ng) : p_out, shadow_dir, tmax, splitmix64(rng.next()))) L += beta * f;
            }
            glm::vec2 u_env = rng.uniform2();
            if (env) {
                EnvironmentLight::Sample es = env->sample(u_env);
                if (es.pdf > 0.0f && glm::dot(es.direction, ng) > 0.0f) {
                    glm::vec3 f = bsdf.eval(es.direction) * es.radiance;
                    if (f.x + f.y + f.z > 0.0f) {
                        float w = power_heuristic(es.pdf, bsdf.pdf(es.direction));
                        bool visible = true;
                        if (settings.env_visibility) {
                            ++rays;
                            visible = !scene.occluded(p_out, es.direction, INFINITY, splitmix64(rng.next()));
                        }
                        if (visible) L += beta * f * (w / es.pdf);
                    }
                }
            }

            // Continue along a sample of the BSDF.
            BsdfSample bs = bsdf.sample(rng.uniform3());
            if (bs.pdf <= 0.0f || (glm::dot(bs.l, ng) <= 0.0f) != bs.transmitted) break;
            beta *= bs.f_cos / bs.pdf;
            bsdf_pdf = bs.pdf;
            // KHR_materials_transmission: the path continues below the surface (next-event
            // estimation sees only the upper side, so the next light it meets counts fully);
            // through a volume (KHR_materials_volume) it leaves where the thickness-scaled
            // refracted view ray does, attenuated along it, as the Khronos viewer models it.
            transmitted = bs.transmitted;
            glm::vec3 exit = p;
            if (bs.transmitted && !bs.diffuse_transmitted && m.transmission.thickness > 0.0f) {
                glm::vec3 ray = transmission::volume_ray(m.normal, wo, m.transmission.thickness, m.transmission.ior,
                                                         glm::vec3(1.0f));
                exit = p + ray;
                beta = transmission::volume_attenuation(beta, glm::length(ray), m.transmission.attenuation_color,
                                                        m.transmission.attenuation_distance);
            }
            if (env && !settings.env_visibility) {
                // The environment unshadowed: its BSDF-sampled half of the MIS here, hit or not.
                L += beta * env->radiance(bs.l) * (bs.transmitted ? 1.0f : power_heuristic(bs.pdf, env->pdf(bs.l)));
                env_counted = true;
            }
            float rr = rng.uniform();
            if (bounce + 1 >= settings.russian_roulette_start) {
                float q = std::min(std::max({beta.x, beta.y, beta.z}), 0.95f);
                if (!(rr < q)) break;
                beta /= q;
            }
            if (!(beta.x + beta.y + beta.z > 0.0f)) break;
            origin = bs.transmitted ? offset_ray(exit, -ng) : offset_ray(p, ng);
            dir = bs.l;
        }
        return L;
    }
};

// Camera rays through points of the image (NDC), from the near plane; the direction through the
// mid-depth point (better conditioned than the far plane's, which a far/near of 1000 puts far out).
struct CameraRays {
    glm::mat4 inv_vp;
    explicit CameraRays(const CameraSetup& camera) : inv_vp(glm::inverse(camera.projection * camera.view)) {}
    glm::vec3 unproject(glm::vec2 ndc, float z) const {
        glm::vec4 p = inv_vp * glm::vec4(ndc, z, 1.0f);
        return glm::vec3(p) / p.w;
    }
    void ray(glm::vec2 ndc, glm::vec3& origin, glm::vec3& direction) const {
        origin = unproject(ndc, -1.0f);
        direction = glm::normalize(unproject(ndc, 0.0f) - origin);
    }
};

}  // namespace

ImageF trace_image(const TraceScene& tscene, const CameraSetup& camera, const std::vector<LightInstance>& lights,
                   const EnvironmentLight* environment, const TraceSettings& settings, TraceStats* stats,
                   const TraceProgress& progress) {
    auto t0 = Clock::now();
    const int W = settings.width, H = settings.height;
    if (W < 1 || H < 1) throw Error("trace", "", "empty image size");
    const TraceScene::Impl& scene = tscene.impl();
    const CameraRays rays_of(camera);

    std::vector<float> sum(std::size_t(W) * H * 4, 0.0f);  // RGB radiance, coverage
    constexpr int kTile = 32;
    const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (H + kTile - 1) / kTile;
    const std::size_t tiles = std::size_t(tiles_x) * tiles_y;
    const int total = std::max(settings.samples, 1);
    std::atomic<std::uint64_t> rays{0};
    std::atomic<std::size_t> tiles_done{0};
    TraceStats st;
    int done = 0;
    int pass_size = 1;
    while (done < total) {
        const int s0 = done, s1 = std::min(total, done + pass_size);
        parallel_for(
            tiles,
            [&](std::size_t tile) {
                Integrator integ{scene, lights, environment, settings};
                const int tx = int(tile % std::size_t(tiles_x)) * kTile, ty = int(tile / std::size_t(tiles_x)) * kTile;
                // Camera rays in packets of 8 (pixel by pixel, sample by sample within a pixel, as
                // a single-ray loop would visit them), then each path on its own.
                struct Lane {
                    int x = 0, y = 0;
                    Rng rng{0, 0};
                    glm::vec3 o{0.0f}, d{0.0f};
                };
                Lane lanes[8];
                int active[8] = {};
                glm::vec3 org[8], dirs[8];
                std::uint64_t seeds[8] = {};
                Hit hits[8];
                int n = 0;
                auto flush = [&] {
                    for (int i = n; i < 8; ++i) active[i] = 0;
                    scene.intersect8(active, org, dirs, seeds, hits);
                    for (int i = 0; i < n; ++i) {
                        Lane& ln = lanes[i];
                        bool covered = false;
                        glm::vec3 L = integ.radiance(ln.o, ln.d, ln.rng, covered, &hits[i]);
                        if (!std::isfinite(L.x + L.y + L.z)) L = glm::vec3(0.0f);  // a lost sample, not a NaN pixel
                        float* acc = &sum[(std::size_t(ln.y) * W + ln.x) * 4];
                        acc[0] += L.x;
                        acc[1] += L.y;
                        acc[2] += L.z;
                        acc[3] += covered ? 1.0f : 0.0f;
                    }
                    n = 0;
                };
                for (int y = ty; y < std::min(H, ty + kTile); ++y)
                    for (int x = tx; x < std::min(W, tx + kTile); ++x) {
                        const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(W) + std::uint64_t(x);
                        for (int s = s0; s < s1; ++s) {
                            // The state from (seed, pixel, sample) through the hash; one stream (PCG streams
                            // that share a state are correlated).
                            Lane& ln = lanes[n];
                            ln.x = x;
                            ln.y = y;
                            ln.rng = Rng(splitmix64(splitmix64(settings.seed ^ splitmix64(pixel)) + std::uint64_t(s)), 0);
                            glm::vec2 j = ln.rng.uniform2();
                            glm::vec2 ndc(2.0f * (float(x) + j.x) / float(W) - 1.0f, 1.0f - 2.0f * (float(y) + j.y) / float(H));
                            rays_of.ray(ndc, ln.o, ln.d);
                            org[n] = ln.o;
                            dirs[n] = ln.d;
                            seeds[n] = splitmix64(ln.rng.next());
                            active[n] = 1;
                            if (++n == 8) flush();
                        }
                    }
                if (n > 0) flush();
                rays += integ.rays;
                std::size_t k = ++tiles_done;
                if (progress)
                    progress((double(s0) * double(tiles) + double(k) * double(s1 - s0)) / (double(total) * double(tiles)));
            },
            settings.threads);
        tiles_done = 0;
        done = s1;
        pass_size = std::min(pass_size * 2, 8);
        if (settings.time_limit_s > 0 && done < total && ms_since(t0) >= settings.time_limit_s * 1000.0) {
            st.time_limited = true;
            break;
        }
        if (settings.stop && done < total && settings.stop->load()) {
            st.stopped = true;
            break;
        }
    }
    if (progress) progress(1.0);

    ImageF out(W, H);
    const float inv = 1.0f / float(done);
    const bool env_bg = environment && settings.env_background;
    for (std::size_t i = 0; i < std::size_t(W) * H; ++i) {
        for (int c = 0; c < 3; ++c) out.pixels[i * 4 + std::size_t(c)] = sum[i * 4 + std::size_t(c)] * inv;
        out.pixels[i * 4 + 3] = env_bg ? 1.0f : sum[i * 4 + 3] * inv;
    }
    st.samples = done;
    st.camera_paths = std::uint64_t(W) * std::uint64_t(H) * std::uint64_t(done);
    st.rays = rays;
    st.trace_ms = ms_since(t0);
    if (stats) *stats = st;
    return out;
}

ImageF to_output(const ImageF& radiance, const RenderSettings& s) {
    ImageF out(radiance.width, radiance.height);
    const float exposure = exposure_scale(s.exposure_ev);
    const bool transparent = s.background.w == 0.0f;
    glm::vec3 bg(s.background);
    if (!s.encoding) bg = srgb_to_linear(glm::clamp(bg, 0.0f, 1.0f));
    for (std::size_t i = 0; i < std::size_t(radiance.width) * radiance.height; ++i) {
        const float* p = &radiance.pixels[i * 4];
        float a = std::clamp(p[3], 0.0f, 1.0f);
        glm::vec3 L = glm::vec3(p[0], p[1], p[2]) * exposure;
        float* o = &out.pixels[i * 4];
        glm::vec3 c;
        float alpha = 1.0f;
        if (transparent && s.straight_alpha) {
            // Straight alpha: the covered part's colour, un-premultiplied.
            glm::vec3 t = tone_map(s.tone_mapper, a > 0.0f ? L / a : glm::vec3(0.0f));
            c = s.encoding ? encode_display(*s.encoding, t) : t;
            alpha = a;
        } else {
            glm::vec3 t = tone_map(s.tone_mapper, L);
            c = s.encoding ? encode_display(*s.encoding, t) : t;
            if (transparent) alpha = a;
            else c += (1.0f - a) * bg;
        }
        o[0] = c.x;
        o[1] = c.y;
        o[2] = c.z;
        o[3] = alpha;
    }
    return out;
}

SurfaceImages trace_surfaces(const TraceScene& tscene, const CameraSetup& camera, int width, int height,
                             unsigned threads) {
    if (width < 1 || height < 1) throw Error("trace", "", "empty image size");
    const TraceScene::Impl& scene = tscene.impl();
    const CameraRays rays_of(camera);
    // The view axis (depth is measured along it, as a depth buffer's linear depth).
    const glm::vec3 forward = -glm::vec3(glm::inverse(camera.view)[2]);
    SurfaceImages out;
    out.width = width;
    out.height = height;
    const std::size_t n = std::size_t(width) * std::size_t(height);
    out.depth.assign(n, std::numeric_limits<float>::infinity());
    out.position.assign(n * 3, 0.0f);
    out.normal.assign(n * 3, 0.0f);
    out.geometric_normal.assign(n * 3, 0.0f);
    out.uv.assign(n * 2, 0.0f);
    out.material.assign(n, -1);
    out.node.assign(n, -1);
    parallel_for(
        std::size_t(height),
        [&](std::size_t row) {
            const int y = int(row);
            for (int x = 0; x < width; ++x) {
                // The pixel's centre, as the rasteriser samples it.
                glm::vec2 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f, 1.0f - (float(y) + 0.5f) / float(height) * 2.0f);
                glm::vec3 o, d;
                rays_of.ray(ndc, o, d);
                Hit hit = scene.intersect(o, d, std::numeric_limits<float>::infinity(), 0, true);
                if (!hit.valid()) continue;
                const SurfaceHit sh = scene.surface(hit);
                const Geometry& g = *sh.geometry;
                const glm::vec3 p = sh.p;
                glm::vec3 ng = sh.ng, ns = sh.ns;
                if (glm::dot(ng, d) > 0.0f) {  // a back face (double-sided): the flipped frame, as shading sees it
                    ng = -ng;
                    ns = -ns;
                }
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                out.depth[i] = glm::dot(p - camera.eye, forward);
                for (int c = 0; c < 3; ++c) {
                    out.position[i * 3 + std::size_t(c)] = p[c];
                    out.normal[i * 3 + std::size_t(c)] = ns[c];
                    out.geometric_normal[i * 3 + std::size_t(c)] = ng[c];
                }
                if (!g.uv0.empty()) {
                    out.uv[i * 2] = sh.sp.uv0.x;
                    out.uv[i * 2 + 1] = sh.sp.uv0.y;
                }
                out.material[i] = g.material_index;
                out.node[i] = sh.node;
            }
        },
        threads);
    return out;
}

}  // namespace fresnel::trace
