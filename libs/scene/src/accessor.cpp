#include "accessor.h"
#include "gltf_codes.h"

#include <cstring>

namespace fresnel::gltf {

int component_size(int t) {
    switch (t) {
        case gltf_code::kByte: case gltf_code::kUnsignedByte: return 1;
        case gltf_code::kShort: case gltf_code::kUnsignedShort: return 2;
        case gltf_code::kUnsignedInt: case gltf_code::kFloat: return 4;
        default: return 0;
    }
}

namespace {
int type_components(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}
// Size in bytes of one element, honouring the 4-byte column alignment of matrices.
std::size_t element_size(int comps, int csize, bool matrix) {
    if (!matrix || comps == 16) return std::size_t(comps) * csize;
    int rows = comps == 4 ? 2 : 3;
    std::size_t column = (std::size_t(rows) * csize + 3) & ~std::size_t(3);
    return column * rows;
}
double decode_component(const std::uint8_t* p, int ctype, bool normalized) {
    switch (ctype) {
        case gltf_code::kByte: { std::int8_t v; std::memcpy(&v, p, 1); return normalized ? std::max(v / 127.0, -1.0) : v; }
        case gltf_code::kUnsignedByte: { std::uint8_t v = *p; return normalized ? v / 255.0 : v; }
        case gltf_code::kShort: { std::int16_t v; std::memcpy(&v, p, 2); return normalized ? std::max(v / 32767.0, -1.0) : v; }
        case gltf_code::kUnsignedShort: { std::uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
        case gltf_code::kUnsignedInt: { std::uint32_t v; std::memcpy(&v, p, 4); return normalized ? v / 4294967295.0 : v; }
        case gltf_code::kFloat: { float v; std::memcpy(&v, p, 4); return v; }
    }
    return 0;
}
}  // namespace

AccessorDecoder::AccessorDecoder(const JsonReader& reader, const json& doc,
                                 const std::vector<std::vector<std::uint8_t>>& buffers, std::size_t max_elements,
                                 BudgetCheck check)
    : r_(reader), buffers_(buffers), max_elements_(max_elements), check_(std::move(check)) {
    accessors_ = &r_.array(doc, "accessors", "");
    const json& views = r_.array(doc, "bufferViews", "");
    views_.resize(views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        std::string ptr = "/bufferViews/" + std::to_string(i);
        const json& v = views[i];
        if (!v.is_object()) r_.fail(ptr, "must be an object");
        BufferViewInfo& info = views_[i];
        info.buffer = r_.index(v, "buffer", ptr, buffers_.size(), "buffer", true);
        info.offset = std::size_t(r_.integer(v, "byteOffset", ptr, 0, 0, LLONG_MAX));
        info.length = std::size_t(r_.integer(v, "byteLength", ptr, 0, 1, LLONG_MAX, true));
        info.stride = std::size_t(r_.integer(v, "byteStride", ptr, 0, 4, 252));
        if (info.stride % 4 != 0) r_.fail(ptr + "/byteStride", "must be a multiple of 4");
        std::size_t size = buffers_[std::size_t(info.buffer)].size();
        if (size == 0) {
            info.error = "buffer " + std::to_string(info.buffer) + " has no data";
            info.placeholder = true;
        }
        else if (info.offset > size || info.length > size - info.offset)
            info.error = "byte range [" + std::to_string(info.offset) + ", " + std::to_string(info.offset + info.length) +
                         ") exceeds buffer " + std::to_string(info.buffer) + " of " + std::to_string(size) + " bytes";
    }
}

bool AccessorDecoder::has_data(int index) const {
    if (index < 0 || std::size_t(index) >= accessors_->size()) return true;  // read() reports it
    const json& a = (*accessors_)[std::size_t(index)];
    auto placeholder = [&](const json& obj) {
        if (!obj.is_object()) return false;
        auto it = obj.find("bufferView");
        if (it == obj.end() || !it->is_number_unsigned()) return false;
        std::size_t v = it->get<std::size_t>();
        return v < views_.size() && views_[v].placeholder;
    };
    if (placeholder(a)) return false;
    if (a.is_object() && a.contains("sparse") && a["sparse"].is_object()) {
        const json& sp = a["sparse"];
        if (sp.contains("indices") && placeholder(sp["indices"])) return false;
        if (sp.contains("values") && placeholder(sp["values"])) return false;
    }
    return true;
}

std::span<const std::uint8_t> AccessorDecoder::view_bytes(int view, const std::string& ptr) const {
    if (view < 0 || std::size_t(view) >= views_.size()) r_.fail(ptr, "bufferView does not exist");
    const BufferViewInfo& v = views_[std::size_t(view)];
    if (!v.error.empty()) r_.fail("/bufferViews/" + std::to_string(view), v.error);
    return {buffers_[std::size_t(v.buffer)].data() + v.offset, v.length};
}

void AccessorDecoder::describe(int index, int& components, int& component_type, bool& normalized,
                               std::size_t& count) const {
    std::string ptr = "/accessors/" + std::to_string(index);
    if (index < 0 || std::size_t(index) >= accessors_->size()) r_.fail(ptr, "accessor does not exist");
    const json& a = (*accessors_)[std::size_t(index)];
    if (!a.is_object()) r_.fail(ptr, "must be an object");
    component_type = int(r_.integer(a, "componentType", ptr, 0, 0, 1 << 20, true));
    if (component_size(component_type) == 0)
        r_.fail(ptr + "/componentType", "invalid component type " + std::to_string(component_type));
    components = type_components(r_.string(a, "type", ptr));
    if (components == 0) r_.fail(ptr + "/type", "missing or invalid type '" + r_.string(a, "type", ptr) + "'");
    normalized = r_.boolean(a, "normalized", ptr, false);
    if (normalized && (component_type == gltf_code::kFloat || component_type == gltf_code::kUnsignedInt))
        r_.fail(ptr + "/normalized", "only 8- and 16-bit integer accessors can be normalized");
    count = std::size_t(r_.integer(a, "count", ptr, 0, 1, (long long)max_elements_, true));
}

std::span<const std::uint8_t> AccessorDecoder::view_range(int view, std::size_t offset, std::size_t count,
                                                          std::size_t elem_size, std::size_t& stride,
                                                          const std::string& ptr) const {
    const BufferViewInfo& v = views_[std::size_t(view)];
    if (!v.error.empty()) r_.fail("/bufferViews/" + std::to_string(view), v.error);
    stride = v.stride ? v.stride : elem_size;
    if (stride < elem_size)
        r_.fail(ptr, "byteStride " + std::to_string(stride) + " of bufferView " + std::to_string(view) +
                         " is smaller than the element size " + std::to_string(elem_size));
    // Last byte read: offset + stride*(count-1) + elem_size, computed without overflow.
    unsigned __int128 end = (unsigned __int128)stride * (count - 1) + offset + elem_size;
    if (end > v.length)
        r_.fail(ptr, "reads " + std::to_string((unsigned long long)std::min<unsigned __int128>(end, ~0ull)) +
                         " bytes from bufferView " + std::to_string(view) + " of " + std::to_string(v.length) + " bytes");
    const auto& buf = buffers_[std::size_t(v.buffer)];
    return {buf.data() + v.offset + offset, std::size_t(end)};
}

void AccessorDecoder::read_elements(std::span<const std::uint8_t> bytes, std::size_t stride, std::size_t count,
                                    int comps, int ctype, bool normalized, bool matrix, double* out,
                                    std::size_t out_stride) const {
    int csize = component_size(ctype);
    int rows = comps == 4 ? 2 : comps == 9 ? 3 : 4;
    std::size_t column = matrix ? ((std::size_t(rows) * csize + 3) & ~std::size_t(3)) : 0;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* e = bytes.data() + i * stride;
        for (int c = 0; c < comps; ++c) {
            std::size_t off = matrix ? (c / rows) * column + (c % rows) * csize : std::size_t(c) * csize;
            out[i * out_stride + c] = decode_component(e + off, ctype, normalized);
        }
    }
}

AccessorData AccessorDecoder::read(int index) const {
    AccessorData d;
    describe(index, d.components, d.component_type, d.normalized, d.count);
    std::string ptr = "/accessors/" + std::to_string(index);
    const json& a = (*accessors_)[std::size_t(index)];
    const std::string type = r_.string(a, "type", ptr);
    bool matrix = type.rfind("MAT", 0) == 0;
    int csize = component_size(d.component_type);
    std::size_t elem = element_size(d.components, csize, matrix);
    if ((unsigned __int128)d.count * d.components > max_elements_)
        r_.fail(ptr + "/count", "accessor has more than the limit of " + std::to_string(max_elements_) + " values");
    check_budget(d.count * std::size_t(d.components) * sizeof(double), ptr);
    d.values.assign(d.count * std::size_t(d.components), 0.0);

    int view = r_.index(a, "bufferView", ptr, views_.size(), "bufferView");
    if (view >= 0) {
        std::size_t offset = std::size_t(r_.integer(a, "byteOffset", ptr, 0, 0, LLONG_MAX));
        if (offset % std::size_t(csize) != 0)
            r_.fail(ptr + "/byteOffset", "must be a multiple of the component size " + std::to_string(csize));
        std::size_t stride = 0;
        auto bytes = view_range(view, offset, d.count, elem, stride, ptr);
        read_elements(bytes, stride, d.count, d.components, d.component_type, d.normalized, matrix, d.values.data(),
                      std::size_t(d.components));
    } else if (r_.has(a, "byteOffset")) {
        r_.fail(ptr + "/byteOffset", "byteOffset without a bufferView");
    }

    const json* sparse = r_.find(a, "sparse");
    if (sparse) {
        std::string sp = ptr + "/sparse";
        if (!sparse->is_object()) r_.fail(sp, "must be an object");
        std::size_t n = std::size_t(r_.integer(*sparse, "count", sp, 0, 1, (long long)d.count, true));
        const json& idx = r_.object(*sparse, "indices", sp);
        const json& val = r_.object(*sparse, "values", sp);
        if (idx.empty()) r_.fail(sp + "/indices", "is required");
        if (val.empty()) r_.fail(sp + "/values", "is required");
        std::string ip = sp + "/indices", vp = sp + "/values";
        int iview = r_.index(idx, "bufferView", ip, views_.size(), "bufferView", true);
        int ictype = int(r_.integer(idx, "componentType", ip, 0, 0, 1 << 20, true));
        if (ictype != gltf_code::kUnsignedByte && ictype != gltf_code::kUnsignedShort && ictype != gltf_code::kUnsignedInt)
            r_.fail(ip + "/componentType", "sparse indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        if (views_[std::size_t(iview)].stride) r_.fail(ip + "/bufferView", "sparse indices' bufferView must not have byteStride");
        std::size_t ioff = std::size_t(r_.integer(idx, "byteOffset", ip, 0, 0, LLONG_MAX));
        std::size_t istride = 0;
        auto ibytes = view_range(iview, ioff, n, std::size_t(component_size(ictype)), istride, ip);
        int vview = r_.index(val, "bufferView", vp, views_.size(), "bufferView", true);
        if (views_[std::size_t(vview)].stride) r_.fail(vp + "/bufferView", "sparse values' bufferView must not have byteStride");
        std::size_t voff = std::size_t(r_.integer(val, "byteOffset", vp, 0, 0, LLONG_MAX));
        std::size_t vstride = 0;
        auto vbytes = view_range(vview, voff, n, elem, vstride, vp);
        std::vector<double> sidx(n), svals(n * std::size_t(d.components));
        read_elements(ibytes, istride, n, 1, ictype, false, false, sidx.data(), 1);
        read_elements(vbytes, vstride, n, d.components, d.component_type, d.normalized, matrix, svals.data(),
                      std::size_t(d.components));
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t target = std::size_t(sidx[i]);
            if (target >= d.count)
                r_.fail(ip, "sparse index " + std::to_string(target) + " is out of range for " + std::to_string(d.count) +
                                " elements");
            std::copy_n(&svals[i * std::size_t(d.components)], d.components, &d.values[target * std::size_t(d.components)]);
        }
    }
    return d;
}

}  // namespace fresnel::gltf
