// smithlab/registry.hpp -- NDFs by name, and the spec strings that name them: "gtr(alpha=0.3, gamma=1.5)".
//
// A registry is a value, not a global: the CLI builds one, a user adds to it. Registering an NDF is one call:
//     registry.add({.name = "mine", .parameters = {"alpha"}, .description = "...",
//                          .examples = {"mine(alpha=0.1)", "mine(alpha=1e-4)"}},
//                  [](const smithlab::NdfParams& p) { return MyNdf{p.at("alpha")}; });
// `examples` are the parameter points the per-distribution tests and `smithlab check --all` run; put the stiff
// corners of your NDF there.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/spec.hpp"

namespace smithlab {

class NdfParams {
public:
    NdfParams(std::string ndf, std::map<std::string, double> values) : ndf_(std::move(ndf)), values_(std::move(values)) {}
    double at(const std::string& key) const;  // throws input_error naming the missing key
private:
    std::string ndf_;
    std::map<std::string, double> values_;
};

struct NdfInfo {
    std::string name;
    std::vector<std::string> parameters;  // in canonical order
    std::string description;
    std::vector<std::string> examples;  // spec strings, stiff corners included
};

class NdfRegistry {
public:
    using Factory = std::function<AnyNdf(const NdfParams&, NdfSpec canonical_spec)>;

    // Register an NDF type: the factory builds it from validated-present parameters and checks their ranges.
    template <class Make>
    void add(NdfInfo info, Make make) {
        add_erased(std::move(info), [make](const NdfParams& p, NdfSpec spec) { return AnyNdf(make(p), std::move(spec)); });
    }

    AnyNdf make(std::string_view spec) const;  // throws input_error: unknown NDF, unknown/missing parameter, bad value
    // The same without a spec string, make("gtr", {{"alpha", 0.3}, {"gamma", 1.5}}); also input_error for a
    // parameter given twice. A spec is text to show (AnyNdf::spec), not the way to build an NDF in code.
    AnyNdf make(std::string_view family, const std::vector<std::pair<std::string, double>>& params) const;
    const NdfInfo* find(std::string_view name) const;
    std::vector<const NdfInfo*> list() const;  // in registration order

private:
    void add_erased(NdfInfo info, Factory make);
    std::vector<std::pair<NdfInfo, Factory>> entries_;
};

// ggx, beckmann, blinn, student.
void register_core_ndfs(NdfRegistry& registry);

}  // namespace smithlab
