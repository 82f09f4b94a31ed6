#include "smithlab/walk/facets.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/walk/material_catalogue.hpp"

namespace smithlab::walk {

namespace detail {

double hammon_lobe_cos(double u) {
    auto Y =
        [](double c) {  // Horner form of the slide's polynomial, c^3 (7/2 - 21/4 c + 21/5 c^2 - 7/4 c^3 + 3/10 c^4)
            return c * c * c * (3.5 + c * (-5.25 + c * (4.2 + c * (-1.75 + c * 0.3))));
        };
    auto dY = [](double c) {  // (21/10) c (1 - (1 - c)^5)
        const double t = 1.0 - c, t2 = t * t;
        return 2.1 * c * (1.0 - t2 * t2 * t);
    };
    if (!(u > 0.0)) return 0.0;
    if (!(u < 1.0)) return 1.0;
    // Shirley's rational first guess, as printed on the slide; below u = 1e-3, where it is poor (it tends to 0.011,
    // not 0), the leading term of Y = 7/2 c^3 (1 + O(c)). From either, Newton's method is quadratic: the step that
    // is below 2^-26 c leaves an error of about its square, 2^-52 (tests/test_walk.cpp: within 2e-15 of a long-double
    // inversion; 3 steps on average). A step out of the bracket [lo, hi] that the residuals keep is replaced by
    // bisection.
    double c = u < 1e-3
        ? std::cbrt(u / 3.5)
        : (0.0114813 + u * (154.4 + u * (13002.4 + u * 38295.9))) / (1.0 + u * (1483.57 + u * (33596.4 + u * 16520.2)));
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 100; ++i) {
        const double r = Y(c) - u;
        if (r == 0.0) return c;
        (r > 0.0 ? hi : lo) = c;
        double next = c - r / dY(c);
        if (std::abs(next - c) <= 0x1p-26 * c) return next;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        c = next;
    }
    return c;
}

}  // namespace detail

namespace {

// The parameters of a material spec by key, each checked against its range; unknown keys refused.
class MaterialParams {
public:
    MaterialParams(const NdfSpec& spec, std::initializer_list<std::string> keys) : name_(spec.name) {
        for (const auto& [key, value] : spec.params) {
            if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
                std::string known;
                for (const std::string& k : keys) known += (known.empty() ? "" : ", ") + k;
                throw input_error("material '" + name_ + "': unknown parameter '" + key + "'" +
                                  (known.empty() ? " (it takes none)" : " (it takes " + known + ")"));
            }
            values_[key] = value;
        }
    }
    double get(const std::string& key, double fallback, double lo, double hi) const {
        const auto it = values_.find(key);
        if (it == values_.end()) {
            if (std::isnan(fallback))
                throw input_error("material '" + name_ + "': parameter '" + key + "' is required");
            return fallback;
        }
        const double v = it->second;
        require(v >= lo && v <= hi, "material '" + name_ + "': " + key, "in [" + num(lo) + ", " + num(hi) + "]", v);
        return v;
    }

private:
    static std::string num(double x) { return format_printf("%g", x); }
    std::string name_;
    std::map<std::string, double> values_;
};

constexpr double required = NAN;

}  // namespace

Material parse_material(std::string_view text) {
    const NdfSpec spec = parse_spec(text, "material spec");
    const std::string& n = spec.name;
    if (n == "mirror") {
        MaterialParams p(spec, {});
        return Mirror{};
    }
    if (n == "conductor") {
        MaterialParams p(spec, {"eta", "k"});
        return Conductor{p.get("eta", required, 1e-6, 1e6), p.get("k", required, 0.0, 1e6)};
    }
    if (n == "lambert") {
        MaterialParams p(spec, {"albedo"});
        return Lambert{p.get("albedo", 1.0, 0.0, 1.0)};
    }
    if (n == "fresnel-diffuse") {
        MaterialParams p(spec, {"f0", "albedo"});
        return FresnelDiffuse{p.get("f0", 0.02, 0.0, 1.0), p.get("albedo", 1.0, 0.0, 1.0)};
    }
    if (n == "dielectric") {
        MaterialParams p(spec, {"eta"});
        return Dielectric{p.get("eta", 1.5, 1e-3, 1e3)};
    }
    std::string known;
    for (const MaterialInfo& m : material_catalogue) known += (known.empty() ? "" : ", ") + std::string(m.spec);
    throw input_error("unknown material '" + n + "' (known: " + known + ")");
}

std::string format_material(const Material& material) {
    struct Format {
        std::string operator()(const Mirror&) const { return "mirror"; }
        std::string operator()(const Conductor& c) const {
            return format_spec({"conductor", {{"eta", c.eta}, {"k", c.k}}});
        }
        std::string operator()(const Lambert& l) const { return format_spec({"lambert", {{"albedo", l.albedo}}}); }
        std::string operator()(const FresnelDiffuse& f) const {
            return format_spec({"fresnel-diffuse", {{"f0", f.f0}, {"albedo", f.albedo}}});
        }
        std::string operator()(const Dielectric& d) const { return format_spec({"dielectric", {{"eta", d.eta}}}); }
    };
    return std::visit(Format{}, material);
}

bool has_diffuse(const Material& material) {
    if (const auto* l = std::get_if<Lambert>(&material)) return l->albedo > 0.0;
    if (const auto* f = std::get_if<FresnelDiffuse>(&material)) return f->albedo > 0.0;
    return false;
}

bool transmits(const Material& material) { return std::holds_alternative<Dielectric>(material); }

bool dirac_at(const Material& material, const Vec3& wi, const Vec3& wo) {
    const auto* d = std::get_if<Dielectric>(&material);
    return d && d->eta == 1.0 && (wi + wo).norm() <= 1e-9;
}

}  // namespace smithlab::walk
