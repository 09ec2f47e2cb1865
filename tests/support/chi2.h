#pragma once
// The chi-squared goodness-of-fit test that the sampling tests share (libs/material's samplers,
// libs/trace's): the distribution's upper tail, and the statistic from observed and expected
// counts per cell with small cells pooled, as pbrt-v4's and Mitsuba's tests pool them.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <string>
#include <vector>

namespace fresnel::test {

// The regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a): the series
// below a + 1, Lentz's continued fraction above (Numerical Recipes 6.2).
inline double gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    const double log_prefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        // P(a, x) = e^-x x^a / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n))
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (term < sum * 1e-15) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
    }
    // Q(a, x) = e^-x x^a / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...))
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(log_prefix) * h;
}

// P(X >= chi2) for X chi-squared with `dof` degrees of freedom.
inline double chi2_p_value(double chi2, int dof) { return gamma_q(0.5 * dof, 0.5 * chi2); }

struct Chi2Result {
    double chi2 = 0, p_value = 0;
    int dof = 0;
    std::string message;  // why the test failed outright (samples where the pdf is 0, ...)
};

// The statistic of `observed` against `expected` counts per cell (`samples` drawn in all).
// Cells are pooled in order of increasing expectation: those below 5 go into one pooled cell,
// and so do the next ones until the pool itself expects at least 5. A cell whose expectation
// is 0 may still hold a sliver of the support (the VNDF's v.h = 0 boundary); as in pbrt and
// Mitsuba, only more than 1e-5 of the samples there fails the test, fewer are pooled.
inline Chi2Result chi2_from_counts(const std::vector<double>& observed, const std::vector<double>& expected,
                                   double samples) {
    Chi2Result r;
    std::vector<std::size_t> order(expected.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
    const double min_expected = 5.0;
    double pooled_obs = 0, pooled_exp = 0;
    for (std::size_t idx : order) {
        if (expected[idx] <= 0.0) {
            pooled_obs += observed[idx];
            if (observed[idx] > 1e-5 * samples) {
                r.message = std::to_string(int(observed[idx])) + " samples in a cell where the pdf is 0 (cell " +
                            std::to_string(idx) + ")";
                return r;
            }
        } else if (expected[idx] < min_expected || (pooled_exp > 0 && pooled_exp < min_expected)) {
            pooled_obs += observed[idx];
            pooled_exp += expected[idx];
        } else {
            double diff = observed[idx] - expected[idx];
            r.chi2 += diff * diff / expected[idx];
            ++r.dof;
        }
    }
    if (pooled_exp > 0 || pooled_obs > 0) {
        double diff = pooled_obs - pooled_exp;
        r.chi2 += diff * diff / std::max(pooled_exp, 1e-300);
        ++r.dof;
    }
    r.dof -= 1;
    if (r.dof < 1) {
        r.message = "fewer than two cells after pooling";
        return r;
    }
    r.p_value = chi2_p_value(r.chi2, r.dof);
    return r;
}

}  // namespace fresnel::test
