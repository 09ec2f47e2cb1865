#include "fresnel/scene/animation.h"

#include <algorithm>
#include <cmath>

namespace fresnel {

namespace {

// Which keyframes bracket t: k0 <= k1 and the fraction u in [0, 1] between them (k0 == k1
// before the first keyframe, after the last, and for single-keyframe samplers).
struct Bracket {
    std::size_t k0 = 0, k1 = 0;
    float u = 0.0f, dt = 0.0f;
};

Bracket bracket(const std::vector<float>& times, float t) {
    Bracket b;
    std::size_t n = times.size();
    if (n == 0 || !(t > times.front())) return b;  // NaN t takes the first keyframe
    if (t >= times.back()) {
        b.k0 = b.k1 = n - 1;
        return b;
    }
    // The first keyframe after t; times are strictly increasing, so 1 <= k1 <= n - 1.
    std::size_t k1 = std::size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    b.k0 = k1 - 1;
    b.k1 = k1;
    b.dt = times[k1] - times[b.k0];
    b.u = b.dt > 0 ? std::clamp((t - times[b.k0]) / b.dt, 0.0f, 1.0f) : 0.0f;
    return b;
}

// Start of keyframe k's value (CUBICSPLINE: its middle element of three).
const float* value_at(const AnimationSampler& s, std::size_t k) {
    std::size_t w = std::size_t(s.width);
    return s.interpolation == Interpolation::CubicSpline ? &s.output[(3 * k + 1) * w] : &s.output[k * w];
}

}  // namespace

bool AnimationSampler::consistent() const {
    if (width <= 0) return false;
    std::size_t per = interpolation == Interpolation::CubicSpline ? 3 : 1;
    return output.size() == input.size() * per * std::size_t(width);
}

float Animation::start() const {
    bool any = false;
    float t = 0.0f;
    for (const auto& s : samplers)
        if (!s.input.empty()) t = any ? std::min(t, s.input.front()) : s.input.front(), any = true;
    return t;
}

float Animation::end() const {
    bool any = false;
    float t = 0.0f;
    for (const auto& s : samplers)
        if (!s.input.empty()) t = any ? std::max(t, s.input.back()) : s.input.back(), any = true;
    return t;
}

void sample(const AnimationSampler& s, float t, std::span<float> out) {
    if (s.input.empty() || !s.consistent()) return;
    std::size_t w = std::size_t(s.width);
    Bracket b = bracket(s.input, t);
    const float* v0 = value_at(s, b.k0);
    if (b.k0 == b.k1 || s.interpolation == Interpolation::Step) {
        std::copy(v0, v0 + w, out.begin());
        return;
    }
    const float* v1 = value_at(s, b.k1);
    float u = b.u;
    if (s.interpolation == Interpolation::Linear) {
        for (std::size_t c = 0; c < w; ++c) out[c] = v0[c] + (v1[c] - v0[c]) * u;
        return;
    }
    // Cubic Hermite (glTF 2.0 Appendix C): b_k = out-tangent of k, a_{k+1} = in-tangent of k+1.
    const float* out_tangent0 = v0 + w;  // element 3k+2
    const float* in_tangent1 = v1 - w;   // element 3(k+1)+0
    float u2 = u * u, u3 = u2 * u;
    float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (std::size_t c = 0; c < w; ++c)
        out[c] = h00 * v0[c] + h10 * b.dt * out_tangent0[c] + h01 * v1[c] + h11 * b.dt * in_tangent1[c];
}

std::vector<float> sample(const AnimationSampler& s, float t) {
    std::vector<float> out(std::size_t(std::max(s.width, 0)), 0.0f);
    sample(s, t, out);
    return out;
}

glm::quat slerp_shortest(const glm::quat& a, glm::quat const& b_in, float u) {
    glm::quat b = b_in;
    float d = glm::dot(a, b);
    if (d < 0.0f) {
        b = -b;
        d = -d;
    }
    glm::quat r;
    if (d > 0.9995f) {
        r = a * (1.0f - u) + b * u;  // nearly parallel: normalised lerp
    } else {
        float theta = std::acos(std::min(d, 1.0f));
        float s = std::sin(theta);
        r = a * (std::sin((1.0f - u) * theta) / s) + b * (std::sin(u * theta) / s);
    }
    float len = glm::length(r);
    return len > 0 ? r / len : glm::quat(1, 0, 0, 0);
}

glm::quat sample_rotation(const AnimationSampler& s, float t) {
    auto normalised = [](glm::quat q) {
        float len = glm::length(q);
        return len > 0 && std::isfinite(len) ? q / len : glm::quat(1, 0, 0, 0);
    };
    if (s.width != 4 || s.input.empty() || !s.consistent()) return glm::quat(1, 0, 0, 0);
    auto quat_at = [&](std::size_t k) {
        const float* v = value_at(s, k);
        return normalised(glm::quat(v[3], v[0], v[1], v[2]));  // glm: (w, x, y, z)
    };
    if (s.interpolation == Interpolation::Linear) {
        Bracket b = bracket(s.input, t);
        if (b.k0 == b.k1) return quat_at(b.k0);
        return slerp_shortest(quat_at(b.k0), quat_at(b.k1), b.u);
    }
    float v[4];
    sample(s, t, v);
    return normalised(glm::quat(v[3], v[0], v[1], v[2]));
}

}  // namespace fresnel
