#include "correlation/space_filling.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

namespace sb::correlation {
namespace {

double radical_inverse(int index, int base) {
    double result = 0.0;
    double f = 1.0 / base;
    for (int i = index; i > 0; i /= base) {
        result += f * (i % base);
        f /= base;
    }
    return result;
}

}  // namespace

std::vector<std::vector<double>> halton(int count, int dimensions, int skip) {
    static constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29};
    if (dimensions < 1 || dimensions > 10) {
        throw std::invalid_argument("halton: 1 to 10 dimensions");
    }
    std::vector<std::vector<double>> points(static_cast<std::size_t>(std::max(0, count)),
                                            std::vector<double>(dimensions));
    for (int i = 0; i < count; ++i) {
        for (int d = 0; d < dimensions; ++d) points[i][d] = radical_inverse(i + skip, kPrimes[d]);
    }
    return points;
}

std::vector<std::vector<double>> latin_hypercube(int count, int dimensions, std::uint64_t seed) {
    std::mt19937_64 generator(seed);
    std::vector<std::vector<double>> points(static_cast<std::size_t>(std::max(0, count)),
                                            std::vector<double>(dimensions));
    std::vector<int> strata(static_cast<std::size_t>(std::max(0, count)));
    for (int d = 0; d < dimensions; ++d) {
        std::iota(strata.begin(), strata.end(), 0);
        // std::shuffle's algorithm is not fixed by the standard: a Fisher–Yates of our own keeps
        // the design the same on every standard library.
        for (int i = count - 1; i > 0; --i) {
            const auto j = static_cast<int>(generator() % static_cast<std::uint64_t>(i + 1));
            std::swap(strata[i], strata[j]);
        }
        for (int i = 0; i < count; ++i) points[i][d] = (strata[i] + 0.5) / count;
    }
    return points;
}

std::vector<std::vector<double>> axis_stencil(const std::vector<double>& centre, double step) {
    std::vector<std::vector<double>> points;
    for (std::size_t j = 0; j < centre.size(); ++j) {
        for (const double sign : {-1.0, 1.0}) {
            auto v = centre;
            v[j] = std::clamp(centre[j] + sign * step, 0.0, 1.0);
            if (v != centre) points.push_back(v);
        }
    }
    return points;
}

}  // namespace sb::correlation
