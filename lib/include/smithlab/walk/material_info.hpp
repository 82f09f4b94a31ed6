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
    std::string key;        ///< the parameter's name in a spec, such as "eta"
    double fallback = NAN;  ///< the value where the spec leaves it out; NaN: required
    /// The closed range a value must lie in.
    ///@{
    double lo = -INFINITY, hi = INFINITY;
    ///@}
};

/// A material as a registry lists it: "conductor", {eta, k}, "mirror facets of a conductor ...".
struct MaterialInfo {
    std::string name;                           ///< the name a spec uses, such as "conductor"
    std::vector<MaterialParameter> parameters;  ///< in the order front ends list them
    std::string description;                    ///< one line, for `smithlab list` and `--help`
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
    /// The material's name and its values by key (already filled in and checked by the registry).
    MaterialParams(std::string name, std::map<std::string, double> values)
        : name_(std::move(name)), values_(std::move(values)) {}
    double at(const std::string& key) const;           ///< std::out_of_range names a key the material did not declare
    const std::string& name() const { return name_; }  ///< the material's name

private:
    std::string name_;
    std::map<std::string, double> values_;
};

}  // namespace smithlab::walk
