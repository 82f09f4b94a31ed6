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
    std::function<NormalSample(Rng&)> sample;
    std::function<double(const Vec3& m)> pdf;  ///< the density sample() draws from
    double table_error = 0.0;                  ///< its tables' estimate (0 when analytic)
};

struct SamplerInfo {
    enum class Incidence { ignored, upper, any };  // whether wi matters, and where it may be

    std::string name;
    std::string description;
    Incidence incidence;
    std::function<bool(const AnyNdf&)> applies;
    std::function<BoundSampler(const AnyNdf&, const Vec3& wi)> prepare;
};

/// dcos, dcos-table, vndf, vndf-table, vndf-ggx, vndf-beckmann, hammon.
std::vector<SamplerInfo> builtin_samplers();
/// input_error naming the unknown sampler and listing the known ones.
const SamplerInfo& find_sampler(const std::vector<SamplerInfo>& samplers, std::string_view name);
/// Prepared for ndf and wi, after checking that it applies and that wi is a direction it takes (input_error).
BoundSampler prepare(const SamplerInfo& sampler, const AnyNdf& ndf, const Vec3& wi);

}  // namespace smithlab
