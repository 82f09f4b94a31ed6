/// @file
/// smithlab/samplers.hpp -- the samplers by name, for `smithlab sample`, the chi-square tests and the report.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/sampling.hpp"

namespace smithlab {

/// A sampler prepared for one NDF and one direction wi.
struct BoundSampler {
    /// Draws a normal and its pdf.
    std::function<NormalSample(Rng&)> sample;
    std::function<double(const Vec3& m)> pdf;  ///< the density sample() draws from
    double table_error = 0.0;                  ///< its tables' estimate (0 when analytic)
};

/// A sampler by name: what it is, which directions it takes, the NDFs it applies to, and how it is prepared.
struct SamplerInfo {
    /// Whether wi matters, and where it may be: ignored (the D cos samplers), above the surface only, or anywhere.
    enum class Incidence { ignored, upper, any };  // whether wi matters, and where it may be

    /// Its name (`smithlab sample --sampler NAME`) and a one-line description.
    /// @{
    std::string name;
    std::string description;
    /// @}
    /// The directions wi it takes.
    Incidence incidence;
    /// The NDFs it is defined for.
    std::function<bool(const AnyNdf&)> applies;
    /// Prepares it for an NDF and a direction wi (prepare() below checks both first).
    std::function<BoundSampler(const AnyNdf&, const Vec3& wi)> prepare;
};

/// dcos, dcos-table, vndf, vndf-table, vndf-ggx, vndf-beckmann, hammon.
std::vector<SamplerInfo> builtin_samplers();
/// input_error naming the unknown sampler and listing the known ones.
const SamplerInfo& find_sampler(const std::vector<SamplerInfo>& samplers, std::string_view name);
/// Prepared for ndf and wi, after checking that it applies and that wi is a direction it takes (input_error).
BoundSampler prepare(const SamplerInfo& sampler, const AnyNdf& ndf, const Vec3& wi);

}  // namespace smithlab
