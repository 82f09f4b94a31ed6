/// @file
/// smithlab/registry.hpp -- NDFs by name, and the spec strings that name them: "gtr(alpha=0.3, gamma=1.5)".
///
/// A registry is a value, not a global: the CLI builds one, a user adds to it. Registering an NDF is one call:
///     registry.add({.name = "mine", .parameters = {"alpha"}, .description = "...",
///                          .examples = {"mine(alpha=0.1)", "mine(alpha=1e-4)"}},
///                  [](const smithlab::NdfParams& p) { return MyNdf{p.at("alpha")}; });
/// `examples` are the parameter points the per-distribution tests and `smithlab check --all` run; put the stiff
/// corners of your NDF there.
///
/// The registration sees the concrete type the factory returns and records, for it, the walk every command runs
/// (surface.hpp): a registered NDF is traced, fitted and reported as its own type, with no virtual call per bounce.
/// What the commands need to know of a family's parameters comes from its NdfInfo: their names (any of them can be a
/// scene's axis) and, for a family without a parameter `alpha`, how a roughness alpha sets one of them (roughness).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fit/diffuse_registry.hpp"
#include "smithlab/material_registry.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/surface.hpp"

namespace smithlab {

/// The parameters of one spec as an NDF's factory reads them: numbers and texts by key, and the NDF's name for
/// messages.
class NdfParams {
public:
    /// The parameters `values` and `texts` of the NDF named `ndf`.
    NdfParams(std::string ndf, std::map<std::string, double> values, std::map<std::string, std::string> texts = {})
        : ndf_(std::move(ndf)), values_(std::move(values)), texts_(std::move(texts)) {}
    double at(const std::string& key) const;                ///< throws input_error naming the missing key
    const std::string& text(const std::string& key) const;  ///< a text parameter (NdfInfo::text_parameters)
    /// The NDF's name, for messages.
    const std::string& ndf() const { return ndf_; }

private:
    std::string ndf_;
    std::map<std::string, double> values_;
    std::map<std::string, std::string> texts_;
};

/// What the registry knows of an NDF family: its name, parameters, description and example specs, and how a roughness
/// sets it.
struct NdfInfo {
    /// The family's name, as a spec names it ("gtr").
    std::string name;
    std::vector<std::string> parameters;  ///< in canonical order
    /// A one-line description, for `smithlab list`.
    std::string description;
    std::vector<std::string> examples;  ///< spec strings, stiff corners included
    /// For a family without a parameter `alpha`: the parameter a roughness alpha sets (the fitter's alpha axis, a
    /// scene's grid.alpha) and its value at alpha given the family's other parameters, e.g. Blinn-Phong's
    /// n = 2 / alpha^2 - 2 (Walter et al. 2007, sec. 5.2). None: the family cannot be swept over alpha.
    struct Roughness {
        /// The parameter a roughness alpha sets, and its value at alpha given the others.
        /// @{
        std::string parameter;
        std::function<double(double alpha, const NdfParams& others)> from_alpha;
        /// @}
    };
    /// How a roughness alpha sets the family, for a family without a parameter `alpha`.
    std::optional<Roughness> roughness = std::nullopt;
    /// Parameters whose values are text, after the numbers in the canonical spec: a file's path
    /// ("tabulated(file=ndf.csv)"; spec.hpp's grammar).
    std::vector<std::string> text_parameters = {};
    /// Values of parameters that a spec may leave out (left out of the canonical spec where they hold).
    std::vector<std::pair<std::string, double>> defaults = {};
};

/// NDF families by name: each registered with its NdfInfo and a factory, made from spec strings or parameters (the file
/// comment); beside them the facet materials and the diffuse models, so that one value holds every name a front end
/// reads.
class NdfRegistry {
public:
    /// No NDF yet; the built-in facet materials and diffuse models.
    NdfRegistry();

    /// What a registration keeps: the NDF made from checked parameters, as an AnyNdf named by the canonical spec.
    using Factory = std::function<AnyNdf(const NdfParams&, NdfSpec canonical_spec)>;

    /// Register an NDF type: the factory builds it from validated-present parameters and checks their ranges.
    template <class Make>
    void add(NdfInfo info, Make make) {
        using N = std::decay_t<std::invoke_result_t<const Make&, const NdfParams&>>;
        add_erased(std::move(info), [make](const NdfParams& p, NdfSpec spec) {
            N ndf = make(p);
            // An NDF read from a file is known by the file's contents (its content_id), not by its path.
            std::string key, note;
            if constexpr (requires { ndf.content_id(); }) {
                NdfSpec by_contents = spec;
                for (auto& [k, v] : by_contents.texts) v = ndf.content_id();
                key = format_spec(by_contents);
            }
            if constexpr (requires { ndf.note(); }) note = ndf.note();
            AnyNdf any(ndf, std::move(spec));
            any.attach(std::make_shared<const KernelsOf<N>>(std::move(ndf)));
            if (!key.empty()) any.set_key(std::move(key));
            any.set_note(std::move(note));
            return any;
        });
    }

    AnyNdf make(std::string_view spec) const;  ///< throws input_error: unknown NDF, unknown/missing parameter, bad
                                               ///< value
    /// The same without a spec string, make("gtr", {{"alpha", 0.3}, {"gamma", 1.5}}); also input_error for a
    /// parameter given twice. A spec is text to show (AnyNdf::spec), not the way to build an NDF in code.
    AnyNdf make(std::string_view family, const std::vector<std::pair<std::string, double>>& params,
                const std::vector<std::pair<std::string, std::string>>& texts = {}) const;
    /// The family at roughness alpha, its other parameters given: alpha itself where the family has that parameter,
    /// else the one its roughness sets; input_error where it has neither.
    AnyNdf make_at_alpha(std::string_view family, double alpha,
                         const std::vector<std::pair<std::string, double>>& others,
                         const std::vector<std::pair<std::string, std::string>>& texts = {}) const;
    /// Every text parameter any registered NDF declares (for a spec parser, spec.hpp).
    std::vector<std::string> text_keys() const;
    /// The family named `name`, or nullptr.
    const NdfInfo* find(std::string_view name) const;
    std::vector<const NdfInfo*> list() const;  ///< in registration order

    /// The facet materials a front end with this registry reads by name (material_registry.hpp): the built-in ones,
    /// and those added to it.
    ///@{
    MaterialRegistry& materials() { return materials_; }
    const MaterialRegistry& materials() const { return materials_; }
    ///@}
    /// The diffuse models `smithlab fit` fits, lists and exports (fit/diffuse_registry.hpp): the built-in ones
    /// (fit/diffuse_models.hpp), and those added to it.
    ///@{
    fit::DiffuseRegistry& diffuse_models() { return diffuse_models_; }
    const fit::DiffuseRegistry& diffuse_models() const { return diffuse_models_; }
    ///@}

private:
    void add_erased(NdfInfo info, Factory make);
    std::vector<std::pair<NdfInfo, Factory>> entries_;
    MaterialRegistry materials_;
    fit::DiffuseRegistry diffuse_models_;
};

/// ggx, beckmann, blinn, student, abc.
void register_core_ndfs(NdfRegistry& registry);

}  // namespace smithlab
