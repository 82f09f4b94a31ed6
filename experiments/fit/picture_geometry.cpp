#include "fit/picture_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace smithlab::fit {

namespace {
constexpr double deg = std::numbers::pi / 180.0;
}  // namespace

std::vector<Pixel> sphere_pixels(int P, int light) {
    const double t = light_degrees[light] * deg;
    const Vec3 l(std::sin(t), 0.0, std::cos(t)), v(0.0, 0.0, 1.0);
    std::vector<Pixel> out;
    for (int j = 0; j < P; ++j)
        for (int i = 0; i < P; ++i) {
            const double x = static_cast<double>(2 * i + 1 - P) / P, y = static_cast<double>(P - 1 - 2 * j) / P;
            const double r2 = x * x + y * y;
            if (!(r2 < 1.0)) continue;
            const Vec3 n(x, y, std::sqrt(1.0 - r2));
            const double nv = n.dot(v), nl = n.dot(l);
            if (!(nl > 1e-9) || !(nv > 1e-9)) continue;  // unlit (n.l <= 0): zero, drawn as background
            const Vec3 vt = v - nv * n, lt = l - nl * n;
            const double sv = vt.norm(), sl = lt.norm();
            double c = sv > 1e-12 && sl > 1e-12 ? vt.dot(lt) / (sv * sl) : 1.0;
            c = std::clamp(c, -1.0, 1.0);
            const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
            const double stv = std::sqrt(std::max(0.0, 1.0 - nv * nv)), stl = std::sqrt(std::max(0.0, 1.0 - nl * nl));
            out.push_back({i, j, light, {Vec3(stv, 0.0, nv), Vec3(stl * c, stl * s, nl)}, nl});
        }
    return out;
}

SphereGroup sphere_group(int P) {
    SphereGroup g;
    for (int light = 0; light < 3; ++light) {
        const std::vector<Pixel> px = sphere_pixels(P, light);
        const std::size_t first = g.pixels.size();
        std::vector<long> index(static_cast<std::size_t>(P) * P, -1);  // pixel (i, j) -> position in g.pixels
        for (const Pixel& p : px) {
            index[static_cast<std::size_t>(p.py) * P + p.px] = static_cast<long>(g.pixels.size());
            g.pixels.push_back(p);
            const int mj = P - 1 - p.py;
            if (p.py <= mj) {  // upper half (y >= 0): traced
                g.source.push_back(g.traced.size());
                g.traced.push_back(p.local);
            } else {
                const long m = index[static_cast<std::size_t>(mj) * P + p.px];
                // The mirror is lit whenever this pixel is (n.l is even in y) and came first (smaller j).
                if (m < static_cast<long>(first)) throw std::logic_error("fit: pictures: a sphere pixel has no mirror");
                g.source.push_back(g.source[static_cast<std::size_t>(m)]);
            }
        }
    }
    return g;
}

std::vector<Pair> slice_points(int n) {
    std::vector<Pair> out;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double th = (i + 0.5) * 90.0 / n * deg, td = (j + 0.5) * 90.0 / n * deg;
            out.push_back({Vec3(std::cos(td) * std::sin(th), std::sin(td), std::cos(td) * std::cos(th)),
                           Vec3(std::cos(td) * std::sin(th), -std::sin(td), std::cos(td) * std::cos(th))});
        }
    return out;
}

}  // namespace smithlab::fit
