#pragma once
// Bounds-checked decoding of glTF accessors (all component types, normalized
// integers, byteStride/interleaving, sparse substitution, no bufferView = zeros).
#include <cstdint>
#include <span>
#include <string>
#include <functional>
#include <vector>

#include "json_reader.h"

namespace fresnel::gltf {

struct BufferViewInfo {
    int buffer = -1;
    std::size_t offset = 0, length = 0, stride = 0;  // stride 0 = tightly packed
    std::string error;  // why the view cannot be read (reported when something uses it)
    bool placeholder = false;  // its buffer has no data at all
};

struct AccessorData {
    std::size_t count = 0;
    int components = 0;     // 1..16
    int component_type = 0;  // gltf_code::kByte .. kFloat (gltf_codes.h)
    bool normalized = false;
    std::vector<double> values;  // count * components, dequantized when normalized
};

class AccessorDecoder {
public:
    // `check(bytes, ptr)` is called before `bytes` of decoded values are allocated (it fails
    // the load when they do not fit the memory budget).
    using BudgetCheck = std::function<void(std::size_t bytes, const std::string& ptr)>;
    AccessorDecoder(const JsonReader& reader, const json& doc, const std::vector<std::vector<std::uint8_t>>& buffers,
                    std::size_t max_elements, BudgetCheck check = {});
    // The budget check, for decoders that produce accessor data of their own (Draco).
    void check_budget(std::size_t bytes, const std::string& ptr) const {
        if (check_) check_(bytes, ptr);
    }
    std::size_t accessor_count() const { return accessors_->size(); }
    // False when the accessor's data lives in a placeholder buffer (no uri, no data):
    // such primitives are skipped with a warning rather than failing the file.
    bool has_data(int index) const;
    // The validated byte range of a bufferView; throws if the view is unusable.
    std::span<const std::uint8_t> view_bytes(int view, const std::string& ptr) const;
    // Decodes accessor `index`. `ptr` is the pointer of the reference (for messages).
    AccessorData read(int index) const;
    // Reads the "type" and "componentType" without decoding.
    void describe(int index, int& components, int& component_type, bool& normalized, std::size_t& count) const;

private:
    const JsonReader& r_;
    const json* accessors_;
    std::vector<BufferViewInfo> views_;
    const std::vector<std::vector<std::uint8_t>>& buffers_;
    std::size_t max_elements_;
    BudgetCheck check_;
    void read_elements(std::span<const std::uint8_t> bytes, std::size_t stride, std::size_t count, int comps,
                       int ctype, bool normalized, bool matrix_padding, double* out, std::size_t out_stride) const;
    std::span<const std::uint8_t> view_range(int view, std::size_t offset, std::size_t count, std::size_t elem_size,
                                             std::size_t& stride, const std::string& ptr) const;
};

int component_size(int component_type);

}  // namespace fresnel::gltf
