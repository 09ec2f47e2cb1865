#include "meshopt_decoder.h"

#include <meshoptimizer.h>

#include "meshopt_filters.h"

namespace fresnel::gltf {

namespace {
constexpr const char* kExt = "EXT_meshopt_compression";
constexpr std::size_t kMaxRatio = 256;  // four times the codecs' largest expansion
}

bool is_meshopt_fallback_buffer(const JsonReader& r, const json& buffer) {
    const json& ext = r.object(buffer, "extensions", "");
    const json* m = r.find(ext, kExt);
    return m && m->is_object() && m->value("fallback", false) == true;
}

void decode_meshopt_views(const JsonReader& r, json& doc, std::vector<std::vector<std::uint8_t>>& buffers,
                          std::size_t max_bytes, const std::function<void(std::size_t, const std::string&)>& account) {
    if (!doc.is_object()) return;
    auto views = doc.find("bufferViews");
    if (views == doc.end() || !views->is_array()) return;  // AccessorDecoder reports a non-array
    for (std::size_t i = 0; i < views->size(); ++i) {
        json& v = (*views)[i];
        if (!v.is_object()) continue;  // reported by AccessorDecoder
        std::string vptr = "/bufferViews/" + std::to_string(i);
        const json& exts = r.object(v, "extensions", vptr);
        const json* e = r.find(exts, kExt);
        if (!e) continue;
        std::string ptr = vptr + "/extensions/" + kExt;
        auto fail = [&](const std::string& where, const std::string& what) -> void {
            r.fail(where, std::string(kExt) + ": " + what);
        };
        if (!e->is_object()) fail(ptr, "must be an object");
        int b = r.index(*e, "buffer", ptr, buffers.size(), "buffer", true);
        std::size_t offset = std::size_t(r.integer(*e, "byteOffset", ptr, 0, 0, LLONG_MAX));
        std::size_t length = std::size_t(r.integer(*e, "byteLength", ptr, 0, 1, LLONG_MAX, true));
        std::size_t stride = std::size_t(r.integer(*e, "byteStride", ptr, 0, 1, 256, true));
        std::size_t count = std::size_t(r.integer(*e, "count", ptr, 0, 1, LLONG_MAX, true));
        std::string mode = r.string(*e, "mode", ptr);
        std::string filter = r.string(*e, "filter", ptr, "NONE");
        std::size_t view_length = std::size_t(r.integer(v, "byteLength", vptr, 0, 1, LLONG_MAX, true));

        const auto& src = buffers[std::size_t(b)];
        if (src.empty()) fail(ptr + "/buffer", "buffer " + std::to_string(b) + " has no data");
        if (offset > src.size() || length > src.size() - offset)
            fail(ptr + "/byteLength", "byte range [" + std::to_string(offset) + ", " + std::to_string(offset + length) +
                                          ") exceeds buffer " + std::to_string(b) + " of " + std::to_string(src.size()) +
                                          " bytes");
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0) fail(ptr + "/byteStride", "must be a multiple of 4 for ATTRIBUTES");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) fail(ptr + "/byteStride", "must be 2 or 4 for " + mode);
            if (mode == "TRIANGLES" && count % 3 != 0) fail(ptr + "/count", "must be a multiple of 3 for TRIANGLES");
        } else {
            fail(ptr + "/mode", "must be ATTRIBUTES, TRIANGLES or INDICES (got '" + mode + "')");
        }
        if (filter != "NONE") {
            if (mode != "ATTRIBUTES") fail(ptr + "/filter", "filters apply to ATTRIBUTES only");
            if (filter == "OCTAHEDRAL") {
                if (stride != 4 && stride != 8) fail(ptr + "/byteStride", "must be 4 or 8 for the OCTAHEDRAL filter");
            } else if (filter == "QUATERNION") {
                if (stride != 8) fail(ptr + "/byteStride", "must be 8 for the QUATERNION filter");
            } else if (filter != "EXPONENTIAL") {
                fail(ptr + "/filter", "unknown filter '" + filter + "'");
            }
        }
        // Sizes before anything is allocated: count x stride must fit the view and the limits.
        unsigned __int128 decoded = (unsigned __int128)count * stride;
        if (decoded > view_length)
            fail(ptr + "/count", std::to_string(count) + " elements of " + std::to_string(stride) +
                                     " bytes do not fit the bufferView's byteLength " + std::to_string(view_length));
        // No meshoptimizer stream expands more than 64:1 (vertex codec: 2 header bits per 16
        // bytes; index codecs: a byte per triangle or index), so a small stream that claims
        // a huge view is refused before the view is allocated.
        if ((unsigned __int128)view_length > (unsigned __int128)length * kMaxRatio + 4096)
            fail(vptr + "/byteLength", "a view of " + std::to_string(view_length) + " bytes cannot come from " +
                                           std::to_string(length) + " compressed bytes");
        if (view_length > max_bytes)
            fail(vptr + "/byteLength", "decoded size " + std::to_string(view_length) + " is over the limit of " +
                                           std::to_string(max_bytes) + " bytes");
        account(view_length, vptr);
        std::vector<std::uint8_t> out(view_length, 0);
        const unsigned char* in = src.data() + offset;
        int rc = 0;
        if (mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(out.data(), count, stride, in, length);
        else if (mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(out.data(), count, stride, in, length);
        else rc = meshopt_decodeIndexSequence(out.data(), count, stride, in, length);
        if (rc != 0)
            fail(ptr, "the " + std::to_string(length) + " compressed bytes do not decode to " + std::to_string(count) + " " +
                          mode + " elements of " + std::to_string(stride) + " bytes (meshoptimizer error " +
                          std::to_string(rc) + ")");
        // The filters are ours (meshopt_filters.h): the reference decoder's rounding on every machine.
        if (filter == "OCTAHEDRAL") meshopt_filter_octahedral(out.data(), count, stride);
        else if (filter == "QUATERNION") meshopt_filter_quaternion(out.data(), count, stride);
        else if (filter == "EXPONENTIAL") meshopt_filter_exponential(out.data(), count, stride);
        // The view now reads the decoded bytes like any other.
        buffers.push_back(std::move(out));
        v["buffer"] = buffers.size() - 1;
        v["byteOffset"] = 0;
        v["byteLength"] = view_length;
    }
}

}  // namespace fresnel::gltf
