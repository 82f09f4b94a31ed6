/// @file
/// smithlab/walk/material_info.hpp -- what a facet material tells a registry about itself: its name, its parameters
/// with their defaults and ranges, and a description; and the checked parameters its factory receives.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smithlab::walk {

/// A parameter of a material spec: its key, its value where the spec leaves it out (NaN: required), and the closed
/// range [lo, hi] a value must lie in.
struct MaterialParameter {
    std::string key;
    double fallback = NAN;
    double lo = -INFINITY, hi = INFINITY;
};

/// A material as a registry lists it: "conductor", {eta, k}, "mirror facets of a conductor ...".
struct MaterialInfo {
    std::string name;
    std::vector<MaterialParameter> parameters;
    std::string description;
    /// Whether light goes through it (a two-sided material, facets.hpp): filled in by the registry.
    bool transmits = false;

    /// The spec with its parameters' defaults, as front ends list it: "lambert(albedo=1)", "conductor(eta=, k=)"
    /// (required parameters have no value), "mirror" (none).
    std::string spec() const;
};

/// The parameters of one material spec, each present (its default filled in) and within its range: what a material's
/// factory reads.
class MaterialParams {
public:
    MaterialParams(std::string name, std::map<std::string, double> values)
        : name_(std::move(name)), values_(std::move(values)) {}
    double at(const std::string& key) const;  ///< std::out_of_range names a key the material did not declare
    const std::string& name() const { return name_; }

private:
    std::string name_;
    std::map<std::string, double> values_;
};

}  // namespace smithlab::walk
