#pragma once
// Piecewise-constant distributions for importance sampling (pbrt's Distribution1D/2D):
// sampling by inverting the cumulative sums, with the pdf of every sample next to it.
#include <vector>

#include <glm/vec2.hpp>

namespace fresnel::trace {

// A piecewise-constant density over [0, 1) from n non-negative weights.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::vector<float> weights);
    // A point in [0, 1) and the index of its piece; pdf = density at that point.
    float sample(float u, float& pdf, int& index) const;
    float pdf(int index) const { return total_ > 0 ? weights_[std::size_t(index)] * float(size()) / total_ : 0.0f; }
    int size() const { return int(weights_.size()); }
    double total() const { return total_; }  // sum of the weights

private:
    std::vector<float> weights_;
    std::vector<double> cdf_;  // size() + 1 entries, cdf_[size()] = 1
    double total_ = 0;
};

// A piecewise-constant density over [0, 1)^2 from a width x height grid of weights (row
// major, row 0 at v = 0): the marginal in v, then the conditional in u of the row picked.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(const std::vector<float>& weights, int width, int height);
    glm::vec2 sample(glm::vec2 u, float& pdf) const;
    float pdf(glm::vec2 uv) const;  // density at uv (over [0,1)^2)
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_ = 0, height_ = 0;
    std::vector<Distribution1D> rows_;
    Distribution1D marginal_;
};

// Walker's alias method (Vose's construction): a discrete distribution over n outcomes
// drawn in constant time from one uniform number, whose remainder comes back uniform.
class AliasTable {
public:
    AliasTable() = default;
    explicit AliasTable(const std::vector<float>& weights);
    // The outcome, and in `remainder` a fresh uniform number in [0, 1) from what u had left.
    int sample(float u, float& remainder) const;
    double probability(int i) const { return total_ > 0 ? double(weights_[std::size_t(i)]) / total_ : 0.0; }
    int size() const { return int(entries_.size()); }

private:
    struct Entry {
        float threshold;  // keep i when the coin is below it, else take alias
        int alias;
    };
    std::vector<Entry> entries_;
    std::vector<float> weights_;
    double total_ = 0;
};

}  // namespace fresnel::trace
