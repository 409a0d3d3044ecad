// Roots of beam frequency equations, found numerically for the validation tests.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

namespace sb::structure::testing {

/// The first `count` sign changes of g on (lo, hi], scanned in steps of `step` and refined by
/// bisection to the last bit. The equations below have simple roots spaced by about pi, so a
/// step of 1e-3 cannot step over one.
inline std::vector<double> first_roots(const std::function<double(double)>& g, int count,
                                       double lo = 1e-3, double hi = 30.0, double step = 1e-3) {
    std::vector<double> roots;
    double a = lo;
    double ga = g(a);
    for (double b = lo + step; b <= hi && static_cast<int>(roots.size()) < count; b += step) {
        const double gb = g(b);
        if ((ga < 0.0) != (gb < 0.0)) {
            double left = a;
            double right = b;
            double g_left = ga;
            for (int i = 0; i < 200 && right - left > 1e-15 * right; ++i) {
                const double mid = 0.5 * (left + right);
                const double g_mid = g(mid);
                if ((g_mid < 0.0) == (g_left < 0.0)) {
                    left = mid;
                    g_left = g_mid;
                } else {
                    right = mid;
                }
            }
            roots.push_back(0.5 * (left + right));
        }
        a = b;
        ga = gb;
    }
    return roots;
}

/// Cantilever (free at x = L) whose root at x = 0 is held against translation and restrained
/// in rotation by a spring k. With w = a cosh bx + b sinh bx + c cos bx + d sin bx, the root
/// conditions w(0) = 0, E I w''(0) = k w'(0) and the free end w''(L) = w'''(L) = 0 give
///   R (1 + cosh l cos l) = l (sin l cosh l - cos l sinh l),   l = beta L, R = k L / (E I)
/// (R -> infinity: clamped-free, 1 + cosh l cos l = 0; R = 0: pinned-free, tan l = tanh l;
/// Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1). Divided by cosh l so
/// that it stays finite.
inline double spring_hinged_cantilever(double l, double r) {
    return r * (1.0 / std::cosh(l) + std::cos(l)) - l * (std::sin(l) - std::cos(l) * std::tanh(l));
}

/// Cantilever whose root rests on a translational spring K and a rotational spring k (no
/// fixed DOF): E I w'''(0) = -K w(0), E I w''(0) = k w'(0), free end. The determinant of the
/// four conditions on (a, b, c, d), divided by cosh l, with T = K L^3 / (E I), R = k L / (E I):
///   | l      -R     -l     -R   |
///   | T      l^3     T    -l^3  |
///   | 1      th     -cs/ch -sn/ch |
///   | th     1      sn/ch  -cs/ch |   (th = tanh l, ch = cosh l, cs = cos l, sn = sin l).
inline double elastically_supported_cantilever(double l, double t, double r) {
    const double th = std::tanh(l);
    const double cs = std::cos(l) / std::cosh(l);
    const double sn = std::sin(l) / std::cosh(l);
    const double l3 = l * l * l;
    // Rows: (l, -R, -l, -R), (T, l^3, T, -l^3), (1, th, -cs, -sn), (th, 1, sn, -cs).
    const double m[4][4] = {
        {l, -r, -l, -r}, {t, l3, t, -l3}, {1.0, th, -cs, -sn}, {th, 1.0, sn, -cs}};
    // Laplace expansion along the first two rows (2x2 minors of rows 1-2 times those of 3-4).
    const auto minor = [&](int row, int i, int j) {
        return m[row][i] * m[row + 1][j] - m[row][j] * m[row + 1][i];
    };
    const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    double det = 0.0;
    for (const auto& p : pairs) {
        int rest[2];
        int k = 0;
        for (int c = 0; c < 4; ++c) {
            if (c != p[0] && c != p[1]) rest[k++] = c;
        }
        // (-1)^((1 + 2) + (i + 1) + (j + 1)) for the 0-based columns i, j of rows 1 and 2.
        const int sign = ((p[0] + p[1] + 1) % 2 == 0) ? 1 : -1;
        det += sign * minor(0, p[0], p[1]) * minor(2, rest[0], rest[1]);
    }
    return det;
}

}  // namespace sb::structure::testing
