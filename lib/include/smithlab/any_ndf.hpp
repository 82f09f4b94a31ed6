/// @file
/// smithlab/any_ndf.hpp -- a type-erased NDF, so that the CLI, scene files and the registry can hold any of them.
///
/// AnyNdf is itself an Ndf: the Smith engine works on it unchanged, and it forwards the optional members
/// (slope form, closed-form Lambda, spline Lambda, analytic D cos sampler, the capabilities ggx_alpha and
/// beckmann_alpha) of whatever it holds, answering at run time whether they exist.
#pragma once

#include <concepts>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/spec.hpp"

namespace smithlab {

class NdfKernels;  // surface.hpp

/// Any NDF, type-erased and shared (copies hold the same NDF), with its spec, its key and note, and the walk kernels
/// its registration attached.
class AnyNdf {
public:
    /// Holds `ndf`, named by `spec` (its canonical text is spec()).
    template <Ndf N>
    AnyNdf(N ndf, NdfSpec spec)
        : self_(std::make_shared<const Model<N>>(std::move(ndf))),
          parts_(std::move(spec)),
          spec_(format_spec(parts_)) {}

    /// The held NDF's D and its slope form P22(r^2) (its own, or derived from D: ndf.hpp, slope_density).
    /// @{
    double D(double cos_theta_m) const { return self_->D(cos_theta_m); }
    double slope_density(double r2) const { return self_->slope_density(r2); }
    /// @}
    /// Whether that slope form is the held NDF's own, not derived from its D (ndf.hpp).
    bool has_slope_density() const { return self_->has_slope(); }

    /// Whether the held NDF has a closed-form Lambda.
    bool has_closed_Lambda() const { return self_->has_closed(); }
    /// Throws input_error when the held NDF has no closed form.
    double Lambda(double mu) const;

    /// Whether the held NDF has a spline Lambda.
    bool has_spline_Lambda() const { return self_->has_spline(); }
    /// Throws input_error when the held NDF has no spline.
    double Lambda_spline(double mu) const;

    /// Whether the held NDF has an analytic D cos sampler (Dcos_sf and Dcos_r2, ndf.hpp).
    bool has_Dcos_sampler() const { return self_->has_Dcos(); }
    /// Throw input_error when the held NDF has no analytic D cos sampler.
    /// @{
    double Dcos_sf(double r2) const;
    double Dcos_r2(double v) const;
    /// @}

    /// The quadrature the held NDF's integrals need, where it names one (tabulated.hpp), else none.
    std::optional<Backend> quadrature_backend() const { return self_->quadrature_backend(); }

    /// The alpha of the GGX (Beckmann) distribution the held NDF is, or NaN (ndf.hpp).
    /// @{
    double ggx_alpha() const { return self_->ggx_alpha(); }
    double beckmann_alpha() const { return self_->beckmann_alpha(); }
    /// @}

    /// The canonical spec string, e.g. "gtr(alpha=0.3, gamma=1.5)".
    const std::string& spec() const { return spec_; }
    /// What identifies the NDF in a cache's key: its spec, but for an NDF read from a file, whose file is named by its
    /// contents ("tabulated(file=fnv1a64:...)"): editing the file changes it, moving the file does not.
    const std::string& key() const { return key_.empty() ? spec_ : key_; }
    /// Sets the key (the registry does, for an NDF read from a file).
    void set_key(std::string key) { key_ = std::move(key); }
    /// What the user should know of how the NDF was built ("" mostly): a measured table rescaled to its normalization.
    const std::string& note() const { return note_; }
    /// Sets the note.
    void set_note(std::string note) { note_ = std::move(note); }
    /// Its family name ("gtr") and a parameter by name (input_error if it has none such).
    /// @{
    const std::string& family() const { return parts_.name; }
    double param(std::string_view key) const;
    /// @}
    /// Whether it has a parameter `key`.
    bool has_param(std::string_view key) const;
    /// The parameters as the spec gives them, in the registration's order.
    const NdfSpec& parts() const { return parts_; }

    /// The walk on the held NDF's concrete type (surface.hpp), attached by the registry that made it; null for an
    /// AnyNdf made outside a registry.
    const std::shared_ptr<const NdfKernels>& kernels() const { return kernels_; }
    /// Attaches the walk kernels of the held NDF's concrete type (the registry does, surface.hpp); returns *this.
    AnyNdf& attach(std::shared_ptr<const NdfKernels> kernels) {
        kernels_ = std::move(kernels);
        return *this;
    }

private:
    struct Base {
        virtual ~Base() = default;
        virtual double D(double c) const = 0;
        virtual double slope_density(double r2) const = 0;
        virtual bool has_slope() const = 0;
        virtual bool has_closed() const = 0;
        virtual double closed(double mu) const = 0;
        virtual bool has_spline() const = 0;
        virtual double spline(double mu) const = 0;
        virtual bool has_Dcos() const = 0;
        virtual double Dcos_sf(double r2) const = 0;
        virtual double Dcos_r2(double v) const = 0;
        virtual double ggx_alpha() const = 0;
        virtual double beckmann_alpha() const = 0;
        virtual std::optional<Backend> quadrature_backend() const = 0;
    };
    template <Ndf N>
    struct Model final : Base {
        explicit Model(N n) : ndf(std::move(n)) {}
        double D(double c) const override { return ndf.D(c); }
        double slope_density(double r2) const override { return smithlab::slope_density(ndf, r2); }
        bool has_slope() const override { return smithlab::has_slope_density(ndf); }
        bool has_closed() const override { return smithlab::has_closed_Lambda(ndf); }
        double closed(double mu) const override {
            if constexpr (HasClosedLambda<N>) return ndf.Lambda(mu);
            else return 0.0;  // unreachable: AnyNdf::Lambda checks has_closed() first
        }
        bool has_spline() const override { return smithlab::has_spline_Lambda(ndf); }
        double spline(double mu) const override {
            if constexpr (HasSplineLambda<N>) return ndf.Lambda_spline(mu);
            else return 0.0;  // unreachable: AnyNdf::Lambda_spline checks has_spline() first
        }
        bool has_Dcos() const override { return smithlab::has_Dcos_sampler(ndf); }
        double Dcos_sf(double r2) const override {
            if constexpr (HasDcosSampler<N>) return ndf.Dcos_sf(r2);
            else return 0.0;  // unreachable: AnyNdf checks has_Dcos() first
        }
        double Dcos_r2(double v) const override {
            if constexpr (HasDcosSampler<N>) return ndf.Dcos_r2(v);
            else return 0.0;  // unreachable: AnyNdf checks has_Dcos() first
        }
        double ggx_alpha() const override { return smithlab::ggx_alpha(ndf); }
        double beckmann_alpha() const override { return smithlab::beckmann_alpha(ndf); }
        std::optional<Backend> quadrature_backend() const override {
            if constexpr (requires { ndf.quadrature_backend(); }) return ndf.quadrature_backend();
            else return std::nullopt;
        }
        N ndf;
    };

    std::shared_ptr<const Base> self_;
    NdfSpec parts_;
    std::string spec_, key_, note_;
    std::shared_ptr<const NdfKernels> kernels_;
};

/// Any NDF as an AnyNdf, an AnyNdf as itself: how the type-erased samplers (sampling.hpp) hold one. Spec "unnamed()".
template <Ndf N>
AnyNdf as_any(const N& ndf) {
    if constexpr (std::same_as<N, AnyNdf>) return ndf;
    else return AnyNdf(ndf, NdfSpec{"unnamed", {}});
}

}  // namespace smithlab
