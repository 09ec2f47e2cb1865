#include "meshopt_filters.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace fresnel::gltf {

namespace {

// JavaScript's Math.round: the nearest integer, halves towards +infinity (floor(v + 0.5)
// would round 0.49999999999999994 up).
double js_round(double v) {
    double f = std::floor(v);
    return v - f >= 0.5 ? f + 1.0 : f;
}

// A store into an Int8Array / Int16Array: NaN and infinities become 0, other values are
// truncated and wrapped modulo 2^bits.
template <typename T>
T js_store(double v) {
    if (!std::isfinite(v)) return 0;
    constexpr double kRange = double(1u << (8 * sizeof(T)));
    double m = std::fmod(std::trunc(v), kRange);  // (-range, range)
    if (m < 0) m += kRange;
    auto u = static_cast<std::uint32_t>(m);
    return static_cast<T>(static_cast<std::make_unsigned_t<T>>(u));
}

template <typename T>
T load(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

template <typename T>
void store(std::uint8_t* p, T v) {
    std::memcpy(p, &v, sizeof v);
}

template <typename T>
void octahedral(std::uint8_t* data, std::size_t count, std::size_t stride) {
    constexpr double kMax = double((1 << (8 * sizeof(T) - 1)) - 1);
    for (std::size_t i = 0; i < count; ++i) {
        std::uint8_t* e = data + i * stride;
        double x = load<T>(e), y = load<T>(e + sizeof(T)), one = load<T>(e + 2 * sizeof(T));
        x /= one;
        y /= one;
        const double z = 1.0 - std::fabs(x) - std::fabs(y);
        const double t = std::max(-z, 0.0);
        x -= x >= 0 ? t : -t;
        y -= y >= 0 ? t : -t;
        const double h = kMax / std::sqrt(x * x + y * y + z * z);
        store<T>(e, js_store<T>(js_round(x * h)));
        store<T>(e + sizeof(T), js_store<T>(js_round(y * h)));
        store<T>(e + 2 * sizeof(T), js_store<T>(js_round(z * h)));
        // the fourth component is kept as it is
    }
}

}  // namespace

void meshopt_filter_octahedral(std::uint8_t* data, std::size_t count, std::size_t stride) {
    if (stride == 4) octahedral<std::int8_t>(data, count, stride);
    else if (stride == 8) octahedral<std::int16_t>(data, count, stride);
}

void meshopt_filter_quaternion(std::uint8_t* data, std::size_t count, std::size_t stride) {
    if (stride != 8) return;
    constexpr double kSqrt1_2 = 0.70710678118654752440;  // Math.SQRT1_2
    for (std::size_t i = 0; i < count; ++i) {
        std::uint8_t* e = data + i * stride;
        const std::int16_t in_w = load<std::int16_t>(e + 6);
        const int max_component = in_w & 3;
        const double s = kSqrt1_2 / double(in_w | 3);
        const double x = load<std::int16_t>(e) * s;
        const double y = load<std::int16_t>(e + 2) * s;
        const double z = load<std::int16_t>(e + 4) * s;
        const double w = std::sqrt(std::max(0.0, 1.0 - x * x - y * y - z * z));
        auto put = [&](int component, double v) {
            store<std::int16_t>(e + 2 * std::size_t(component), js_store<std::int16_t>(js_round(v * 32767)));
        };
        put((max_component + 1) % 4, x);
        put((max_component + 2) % 4, y);
        put((max_component + 3) % 4, z);
        put((max_component + 0) % 4, w);
    }
}

void meshopt_filter_exponential(std::uint8_t* data, std::size_t count, std::size_t stride) {
    const std::size_t n = count * (stride / 4);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* e = data + i * 4;
        const auto v = load<std::int32_t>(e);
        const std::int32_t exponent = v >> 24;  // arithmetic: the top byte, signed
        const std::int32_t mantissa = static_cast<std::int32_t>(static_cast<std::uint32_t>(v) << 8) >> 8;
        // 2^exponent as float bits, (exponent + 127) << 23 in 32 bits as the reference's Uint32Array
        const std::uint32_t bits = static_cast<std::uint32_t>(exponent + 127) << 23;
        float scale;
        std::memcpy(&scale, &bits, sizeof scale);
        // A float product rounds the exact product once, as the reference's double product (exact:
        // 24 x 24 bits) stored into a Float32Array; past the float range both give infinity.
        store<float>(e, scale * static_cast<float>(mantissa));
    }
}

}  // namespace fresnel::gltf
