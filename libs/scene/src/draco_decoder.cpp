#include "draco_decoder.h"
#include "gltf_codes.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <limits>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/mesh/mesh_edgebreaker_decoder.h>
#include <draco/compression/mesh/mesh_sequential_decoder.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/varint_decoding.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/metadata_decoder.h>

namespace fresnel::gltf {

namespace {
constexpr const char* kExt = "KHR_draco_mesh_compression";

// The accessor's normalization of an integer read as a double (glTF 2.0, 3.11).
double normalize(double v, int ctype) {
    switch (ctype) {
        case gltf_code::kByte: return std::max(v / 127.0, -1.0);
        case gltf_code::kUnsignedByte: return v / 255.0;
        case gltf_code::kShort: return std::max(v / 32767.0, -1.0);
        case gltf_code::kUnsignedShort: return v / 65535.0;
        default: return v;
    }
}
// The counts a Draco mesh stream declares before its connectivity, read without decoding it, so
// that a hostile stream cannot make Draco allocate for billions of faces or points (Draco sizes
// its corner table and attribute arrays from these fields before it reads what they describe).
struct StreamCounts {
    std::uint64_t faces = 0;
    std::uint64_t points = 0;  // sequential: the point count; edgebreaker: a bound on the vertices
};

// Reads the header, the metadata (by Draco's own decoder: it checks its sizes against the
// buffer) and the connectivity counts, in the layouts of bitstreams 1.x to 2.2.
bool read_stream_counts(const std::uint8_t* data, std::size_t size, StreamCounts& out, std::string& why) {
    draco::DecoderBuffer b;
    b.Init(reinterpret_cast<const char*>(data), size);
    draco::DracoHeader h;
    if (!draco::PointCloudDecoder::DecodeHeader(&b, &h).ok()) return why = "no Draco header", false;
    if (h.encoder_type != draco::TRIANGULAR_MESH) return why = "not a triangle mesh", false;
    if (h.version_major < 1 || h.version_major > draco::kDracoMeshBitstreamVersionMajor ||
        (h.version_major == draco::kDracoMeshBitstreamVersionMajor &&
         h.version_minor > draco::kDracoMeshBitstreamVersionMinor))
        return why = "unknown bitstream version " + std::to_string(h.version_major) + "." +
                     std::to_string(h.version_minor),
               false;
    const std::uint16_t version = DRACO_BITSTREAM_VERSION(h.version_major, h.version_minor);
    b.set_bitstream_version(version);
    if (version >= DRACO_BITSTREAM_VERSION(1, 3) && (h.flags & METADATA_FLAG_MASK)) {
        draco::GeometryMetadata metadata;
        draco::MetadataDecoder md;
        if (!md.DecodeGeometryMetadata(&b, &metadata)) return why = "its metadata cannot be read", false;
    }
    // u32 before bitstream 2.0 (sequential: before 2.2), varints after.
    auto count = [&](bool fixed, std::uint64_t& v) {
        std::uint32_t x = 0;
        bool ok = fixed ? b.Decode(&x) : draco::DecodeVarint(&x, &b);
        v = x;
        return ok;
    };
    if (h.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
        bool fixed = version < DRACO_BITSTREAM_VERSION(2, 2);
        if (!count(fixed, out.faces) || !count(fixed, out.points)) return why = "truncated connectivity", false;
        return true;
    }
    if (h.encoder_method != draco::MESH_EDGEBREAKER_ENCODING) return why = "unknown encoding method", false;
    std::uint8_t traversal = 0;
    if (!b.Decode(&traversal)) return why = "truncated connectivity", false;
    bool fixed = version < DRACO_BITSTREAM_VERSION(2, 0);
    std::uint64_t new_vertices = 0, encoded_vertices = 0, symbols = 0, split_symbols = 0;
    if (version < DRACO_BITSTREAM_VERSION(2, 2) && !count(fixed, new_vertices))
        return why = "truncated connectivity", false;
    std::uint8_t attribute_data = 0;
    if (!count(fixed, encoded_vertices) || !count(fixed, out.faces) || !b.Decode(&attribute_data) ||
        !count(fixed, symbols) || !count(fixed, split_symbols))
        return why = "truncated connectivity", false;
    out.points = encoded_vertices + split_symbols + new_vertices;
    return true;
}
// A Draco mesh decoder that checks what the stream's attribute headers ask for against the
// load's memory budget before any attribute value is decoded: Draco sizes (and zero-fills) each
// attribute's storage from the header's point count and its own component count (up to 255) and
// data type, which the glTF accessors do not bound. PointCloudDecoder::DecodeAllAttributes runs
// after every header was read and before the values are; the check throws there (through
// `check`), which this keeps and the caller rethrows once Draco has returned.
template <class Base>
class BudgetedDecoder : public Base {
public:
    BudgetedDecoder(std::uint64_t values, std::function<void(std::size_t)> check)
        : values_(values), check_(std::move(check)) {}
    std::exception_ptr refused;

protected:
    bool DecodeAllAttributes() override {
        const draco::PointCloud* pc = this->point_cloud();
        std::uint64_t need = 0;
        for (int i = 0; pc && i < pc->num_attributes(); ++i) {
            const draco::PointAttribute* a = pc->attribute(i);
            // The decoded values and Draco's integer copy of them (quantized attributes).
            const std::uint64_t bytes = std::uint64_t(a->num_components()) *
                                        (std::uint64_t(std::max(draco::DataTypeLength(a->data_type()), 1)) + 4);
            need += values_ * bytes;
        }
        try {
            check_(std::size_t(std::min<std::uint64_t>(need, SIZE_MAX)));
        } catch (...) {
            refused = std::current_exception();
            return false;
        }
        return Base::DecodeAllAttributes();
    }

private:
    std::uint64_t values_;  // a bound on the values an attribute can hold
    std::function<void(std::size_t)> check_;
};

// Decodes the mesh stream with a BudgetedDecoder of its encoding; throws what the budget check threw.
draco::StatusOr<std::unique_ptr<draco::Mesh>> decode_budgeted(draco::DecoderBuffer& buffer, std::uint64_t values,
                                                              std::function<void(std::size_t)> check) {
    draco::DecoderBuffer peek = buffer;
    draco::DracoHeader h;
    if (!draco::PointCloudDecoder::DecodeHeader(&peek, &h).ok()) return draco::Status(draco::Status::DRACO_ERROR, "no Draco header");
    auto run = [&](auto decoder) -> draco::StatusOr<std::unique_ptr<draco::Mesh>> {
        auto mesh = std::make_unique<draco::Mesh>();
        draco::DecoderOptions options;
        draco::Status status = decoder->Decode(options, &buffer, mesh.get());
        if (decoder->refused) std::rethrow_exception(decoder->refused);
        if (!status.ok()) return status;
        return mesh;
    };
    if (h.encoder_method == draco::MESH_SEQUENTIAL_ENCODING)
        return run(std::make_unique<BudgetedDecoder<draco::MeshSequentialDecoder>>(values, check));
    if (h.encoder_method == draco::MESH_EDGEBREAKER_ENCODING)
        return run(std::make_unique<BudgetedDecoder<draco::MeshEdgebreakerDecoder>>(values, check));
    return draco::Status(draco::Status::DRACO_ERROR, "unknown encoding method");
}
}  // namespace

std::map<int, AccessorData> decode_draco_primitive(const JsonReader& r, const json& prim, const json& ext,
                                                   const std::string& ptr, const AccessorDecoder& accessors,
                                                   std::size_t max_vertices) {
    auto fail = [&](const std::string& where, const std::string& what) -> void {
        r.fail(where, std::string(kExt) + ": " + what);
    };
    if (!ext.is_object()) fail(ptr, "must be an object");
    int view = r.index(ext, "bufferView", ptr, std::numeric_limits<std::size_t>::max(), "bufferView", true);
    const json& attrs = r.object(ext, "attributes", ptr);
    if (attrs.empty()) fail(ptr + "/attributes", "names no attribute");
    const json& prim_attrs = r.object(prim, "attributes", "");

    // What the accessors promise, checked before anything is decoded.
    struct Want {
        std::string name;
        int accessor = -1, unique_id = -1;
        AccessorData shape;
    };
    std::vector<Want> wants;
    std::size_t points = 0;
    for (auto it = attrs.begin(); it != attrs.end(); ++it) {
        Want w;
        w.name = it.key();
        std::string ap = ptr + "/attributes/" + w.name;
        w.unique_id = int(r.integer(attrs, w.name.c_str(), ptr + "/attributes", 0, 0, INT32_MAX, true));
        w.accessor = r.index(prim_attrs, w.name.c_str(), ptr, accessors.accessor_count(), "accessor");
        if (w.accessor < 0) fail(ap, "attribute " + w.name + " is not among the primitive's attributes");
        accessors.describe(w.accessor, w.shape.components, w.shape.component_type, w.shape.normalized, w.shape.count);
        if (w.shape.count > max_vertices)
            fail(ap, "accessor " + std::to_string(w.accessor) + " has " + std::to_string(w.shape.count) +
                         " elements, over the limit of " + std::to_string(max_vertices));
        if (points && w.shape.count != points)
            fail(ap, "accessor " + std::to_string(w.accessor) + " has " + std::to_string(w.shape.count) +
                         " elements, the others " + std::to_string(points));
        points = w.shape.count;
        wants.push_back(std::move(w));
    }
    int iacc = r.index(prim, "indices", ptr, accessors.accessor_count(), "accessor");
    AccessorData ishape;
    if (iacc >= 0) {
        accessors.describe(iacc, ishape.components, ishape.component_type, ishape.normalized, ishape.count);
        if (ishape.components != 1) fail(ptr, "indices accessor " + std::to_string(iacc) + " must be SCALAR");
        if (ishape.count > max_vertices * 3) fail(ptr, "indices accessor has too many elements");
    }

    auto bytes = accessors.view_bytes(view, ptr + "/bufferView");
    // No stream packs more than 256 points or faces into a byte (Draco's best is a few bits per
    // vertex); a declared count beyond that, or beyond what the accessors say, is refused before
    // Draco allocates for it.
    StreamCounts counts;
    std::string why;
    if (!read_stream_counts(bytes.data(), bytes.size(), counts, why))
        fail(ptr + "/bufferView", "not a Draco mesh stream (" + why + ")");
    const std::uint64_t dense = 1024 + 256 * std::uint64_t(bytes.size());
    if (points > dense)
        fail(ptr, "the accessors promise " + std::to_string(points) + " points from a Draco stream of " +
                      std::to_string(bytes.size()) + " bytes");
    if (iacc >= 0 && counts.faces * 3 != ishape.count)
        fail(ptr, "the Draco stream declares " + std::to_string(counts.faces) + " triangles, indices accessor " +
                      std::to_string(iacc) + " " + std::to_string(ishape.count) + " indices");
    if (counts.faces > dense || counts.faces > std::uint64_t(max_vertices))
        fail(ptr, "the Draco stream declares " + std::to_string(counts.faces) + " triangles in " +
                      std::to_string(bytes.size()) + " bytes");
    if (counts.points > points + counts.faces * 3 || counts.points > dense)
        fail(ptr, "the Draco stream declares " + std::to_string(counts.points) + " vertices, the accessors " +
                      std::to_string(points) + " points");
    // What the decoded mesh and its accessors will hold, within the load's memory budget before
    // Draco allocates (its attributes as the accessors describe them, our doubles, the faces).
    {
        std::uint64_t per_point = 0;
        for (const Want& w : wants) per_point += std::uint64_t(w.shape.components) * (sizeof(double) + 4);
        const std::uint64_t need = std::max<std::uint64_t>(counts.points, points) * per_point + counts.faces * 3 * 16;
        accessors.check_budget(std::size_t(std::min<std::uint64_t>(need, SIZE_MAX)), ptr);
    }
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) fail(ptr + "/bufferView", "not a Draco stream (" + type.status().error_msg_string() + ")");
    if (type.value() != draco::TRIANGULAR_MESH) fail(ptr + "/bufferView", "the Draco stream is not a triangle mesh");
    // An attribute holds at most a value per point or per corner.
    const std::uint64_t values = std::max({std::uint64_t(points), counts.points, counts.faces * 3});
    auto decoded = decode_budgeted(buffer, values, [&](std::size_t bytes) { accessors.check_budget(bytes, ptr); });
    if (!decoded.ok()) fail(ptr + "/bufferView", "cannot decode: " + decoded.status().error_msg_string());
    const draco::Mesh& mesh = *decoded.value();

    if (mesh.num_points() != points)
        fail(ptr, "the Draco mesh has " + std::to_string(mesh.num_points()) + " points, the accessors " +
                      std::to_string(points));
    std::map<int, AccessorData> out;
    for (const Want& w : wants) {
        std::string ap = ptr + "/attributes/" + w.name;
        const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(std::uint32_t(w.unique_id));
        if (!a) fail(ap, "the Draco mesh has no attribute with id " + std::to_string(w.unique_id));
        if (a->num_components() != w.shape.components)
            fail(ap, "the Draco attribute has " + std::to_string(int(a->num_components())) + " components, accessor " +
                         std::to_string(w.accessor) + " " + std::to_string(w.shape.components));
        AccessorData d = w.shape;
        d.values.assign(points * std::size_t(d.components), 0.0);
        bool integral = a->data_type() != draco::DT_FLOAT32 && a->data_type() != draco::DT_FLOAT64;
        bool normalize_here = w.shape.normalized && integral && !a->normalized();
        for (std::size_t i = 0; i < points; ++i) {
            draco::AttributeValueIndex v = a->mapped_index(draco::PointIndex(std::uint32_t(i)));
            if (v.value() >= a->size()) fail(ap, "the Draco attribute maps point " + std::to_string(i) + " out of range");
            double* dst = &d.values[i * std::size_t(d.components)];
            if (!a->ConvertValue<double>(v, std::int8_t(d.components), dst))
                fail(ap, "the Draco attribute's values cannot be read as accessor " + std::to_string(w.accessor) + "'s");
            for (int c = 0; c < d.components; ++c) {
                if (normalize_here) dst[c] = normalize(dst[c], d.component_type);
            }
        }
        out[w.accessor] = std::move(d);
    }
    if (iacc >= 0) {
        std::size_t faces = mesh.num_faces();
        if (faces * 3 != ishape.count)
            fail(ptr, "the Draco mesh has " + std::to_string(faces) + " triangles, indices accessor " +
                          std::to_string(iacc) + " " + std::to_string(ishape.count) + " indices");
        AccessorData d = ishape;
        d.values.resize(faces * 3);
        for (std::size_t f = 0; f < faces; ++f) {
            const auto& face = mesh.face(draco::FaceIndex(std::uint32_t(f)));
            for (int k = 0; k < 3; ++k) d.values[f * 3 + std::size_t(k)] = double(face[k].value());
        }
        out[iacc] = std::move(d);
    }
    return out;
}

}  // namespace fresnel::gltf
