/// @file
/// smithlab/fit/diffuse_model.hpp -- a diffuse model as the fitter takes it: its name and source, its free constants
/// (names, starting values, the ranges where it means what its source says), f in the fitter's one shape, and its
/// GLSL transcription or the explicit statement that it has none. Registered by value (fit/diffuse_registry.hpp); the
/// built-in models are one file each in fit/diffuse/.
///
/// Conventions throughout: f is the BRDF (no cosine); wi points toward the light and wo toward the viewer, unit vectors
/// in the macrosurface frame (z = normal), both with z > 0; every model is symmetric in wi and wo. alpha is the GGX
/// roughness (Disney's perceptual roughness squared), albedo in [0, 1]. The text members are views of static text
/// (literals): a registry keeps the views, not copies.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "smithlab/geometry.hpp"

namespace smithlab::fit {

/// f(wi, wo): the BRDF (no cosine), wi toward the light, wo toward the viewer, unit vectors in the macrosurface frame
/// (z = normal), both z > 0; alpha the GGX roughness; albedo in [0, 1]; c the model's free constants
/// (parameters.size() of them; may be null when there are none). Allocates nothing, never throws.
using DiffuseFn = double (*)(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c);

/// The values a free constant can take where the model means what its source says: lo < c < hi (an infinite bound where
/// none applies), and why. A fit whose constant ends at or beyond a bound has left the model's own domain.
struct ParameterRange {
    /// The open bounds lo `<` c `<` hi; -INFINITY or INFINITY where a side is unbounded.
    ///@{
    double lo = -INFINITY, hi = INFINITY;
    ///@}
    std::string_view why;  ///< one line, e.g. "sigma = s alpha, a slope angle's standard deviation: at most pi/2"
};

/// A model's GLSL transcription (GLSL 3.30, fit/glsl.hpp writes it out). `functions`: the GLSL functions it needs
/// beyond the common helpers (fit/diffuse/common.hpp: smithlab_pi, smithlab_pow5, ...), each a whole definition with
/// its comment, a callee before its caller; an exported library holds each text once, whichever models share it.
/// `call`: what the exported function float f(vec3 L, vec3 V, vec3 N, float alpha, float albedo) returns, a call of a
/// function that `functions` or the common helpers define, {i} standing for the model's constant i (inlined at the
/// exported value), e.g. "smithlab_oren_nayar(L, V, N, {0} * alpha, albedo)".
struct Glsl {
    /// The GLSL function definitions the model needs beyond the common helpers, callees first.
    std::vector<std::string_view> functions;
    /// The exported function's return expression, `{i}` standing for constant i.
    std::string_view call;
};

/// The explicit statement that a model has no GLSL transcription: the fit exports no function for it (models.glsl
/// says so) and the listings say that it has none.
struct NoGlsl {
    explicit NoGlsl() = default;
};
/// The value to write for a model without a GLSL transcription: `.glsl = no_glsl`.
inline constexpr NoGlsl no_glsl{};

/// A Glsl or no_glsl, and nothing else: it has no default, so that a DiffuseModel that names neither does not compile.
class GlslTranscription {
public:
    /// A model with this GLSL transcription.
    GlslTranscription(Glsl glsl) : glsl_(std::move(glsl)) {}
    /// A model without a GLSL transcription.
    GlslTranscription(NoGlsl) {}
    const Glsl* get() const { return glsl_ ? &*glsl_ : nullptr; }  ///< nullptr: the model has none

private:
    std::optional<Glsl> glsl_;
};

/// A diffuse model as the fitter takes it: its name, free constants with published values and ranges, source,
/// f (a DiffuseFn) and its GLSL transcription or no_glsl. Built-in models come from the `*_model()` functions in
/// fit/diffuse/.
struct DiffuseModel {
    std::string_view name = {};                     ///< e.g. "hammon-2017"
    std::vector<std::string_view> parameters = {};  ///< names of the free constants; empty for a fixed baseline
    std::vector<double> published = {};             ///< their published values (a fit's start, the fixed baseline)
    std::string_view source = {};                   ///< citation, one line
    /// The BRDF in the fitter's one shape (conventions of DiffuseFn); required.
    DiffuseFn f = nullptr;
    GlslTranscription glsl;  ///< required: .glsl = Glsl{{functions...}, "call"} or .glsl = no_glsl
    /// Its starting constants make a model of its own, measured as a baseline; false where they make another one
    /// (smithlab-2026 starts at hammon-2017).
    bool own_baseline = true;
    std::vector<ParameterRange> ranges = {};  ///< per parameter (empty: none bounded)
};

/// Where constant i of m is at or beyond its range: the range, else nullptr.
inline const ParameterRange* outside_range(const DiffuseModel& m, std::size_t i, double value) {
    if (i >= m.ranges.size()) return nullptr;
    const ParameterRange& r = m.ranges[i];
    return r.lo < value && value < r.hi ? nullptr : &r;
}

}  // namespace smithlab::fit
