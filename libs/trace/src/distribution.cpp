#include "fresnel/trace/distribution.h"

#include <algorithm>
#include <cmath>

namespace fresnel::trace {

Distribution1D::Distribution1D(std::vector<float> weights) : weights_(std::move(weights)) {
    cdf_.assign(weights_.size() + 1, 0.0);
    for (std::size_t i = 0; i < weights_.size(); ++i) {
        float w = std::isfinite(weights_[i]) ? std::max(weights_[i], 0.0f) : 0.0f;
        weights_[i] = w;
        cdf_[i + 1] = cdf_[i] + double(w);
    }
    total_ = cdf_.back();
    if (total_ > 0) {
        for (double& c : cdf_) c /= total_;
    } else {  // all zero: uniform, so sampling stays defined (pdf() still says 0)
        for (std::size_t i = 0; i < cdf_.size(); ++i) cdf_[i] = double(i) / double(weights_.size());
    }
    cdf_.back() = 1.0;
}

float Distribution1D::sample(float u, float& pdf_out, int& index) const {
    // The last piece whose cdf is <= u (pieces of weight 0 are never chosen).
    auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
    int i = std::clamp(int(it - cdf_.begin()) - 1, 0, size() - 1);
    while (i > 0 && weights_[std::size_t(i)] == 0.0f && total_ > 0) --i;
    index = i;
    double lo = cdf_[std::size_t(i)], hi = cdf_[std::size_t(i) + 1];
    double t = hi > lo ? (double(u) - lo) / (hi - lo) : 0.5;
    pdf_out = pdf(i);
    float x = float((double(i) + std::clamp(t, 0.0, 1.0)) / double(size()));
    return std::min(x, 0x1.fffffep-1f);
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : width_(width), height_(height) {
    std::vector<float> row_sums(std::size_t(height), 0.0f);
    rows_.reserve(std::size_t(height));
    for (int y = 0; y < height; ++y) {
        std::vector<float> row(weights.begin() + std::ptrdiff_t(y) * width, weights.begin() + std::ptrdiff_t(y + 1) * width);
        rows_.emplace_back(std::move(row));
        row_sums[std::size_t(y)] = float(rows_.back().total());
    }
    marginal_ = Distribution1D(std::move(row_sums));
}

glm::vec2 Distribution2D::sample(glm::vec2 u, float& pdf_out) const {
    float pv = 0, pu = 0;
    int row = 0, col = 0;
    float v = marginal_.sample(u.y, pv, row);
    float x = rows_[std::size_t(row)].sample(u.x, pu, col);
    pdf_out = pv * pu;
    return {x, v};
}

float Distribution2D::pdf(glm::vec2 uv) const {
    int x = std::clamp(int(uv.x * float(width_)), 0, width_ - 1);
    int y = std::clamp(int(uv.y * float(height_)), 0, height_ - 1);
    return marginal_.pdf(y) * rows_[std::size_t(y)].pdf(x);
}

AliasTable::AliasTable(const std::vector<float>& weights) : weights_(weights) {
    const std::size_t n = weights_.size();
    for (float& w : weights_) w = std::isfinite(w) ? std::max(w, 0.0f) : 0.0f;
    for (float w : weights_) total_ += double(w);
    entries_.assign(n, Entry{1.0f, 0});
    for (std::size_t i = 0; i < n; ++i) entries_[i].alias = int(i);
    if (n == 0 || total_ <= 0) return;
    std::vector<double> scaled(n);
    std::vector<int> small, large;
    for (std::size_t i = 0; i < n; ++i) {
        scaled[i] = double(weights_[i]) * double(n) / total_;
        (scaled[i] < 1.0 ? small : large).push_back(int(i));
    }
    while (!small.empty() && !large.empty()) {
        int s = small.back(), l = large.back();
        small.pop_back();
        entries_[std::size_t(s)] = Entry{float(scaled[std::size_t(s)]), l};
        scaled[std::size_t(l)] -= 1.0 - scaled[std::size_t(s)];
        if (scaled[std::size_t(l)] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    for (int i : large) entries_[std::size_t(i)] = Entry{1.0f, i};
    for (int i : small) entries_[std::size_t(i)] = Entry{1.0f, i};  // rounding leftovers
}

int AliasTable::sample(float u, float& remainder) const {
    const int n = size();
    float x = u * float(n);
    int i = std::min(int(x), n - 1);
    float coin = std::min(x - float(i), 0x1.fffffep-1f);
    const Entry& e = entries_[std::size_t(i)];
    if (coin < e.threshold) {
        remainder = e.threshold > 0.0f ? coin / e.threshold : 0.0f;
        return i;
    }
    remainder = std::min((coin - e.threshold) / (1.0f - e.threshold), 0x1.fffffep-1f);
    return e.alias;
}

}  // namespace fresnel::trace
