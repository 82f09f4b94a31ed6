#include "fit/trace_points.hpp"

#include <memory>

#include "smithlab/util/parallel.hpp"

namespace smithlab::fitrun {

fit::SplitMoments trace_point(const AnySurface& surface, const walk::Material& m, const TracePoint& p,
                              Estimator estimator, std::uint64_t seed, std::int64_t walks) {
    return estimator == Estimator::albedo ? surface.albedo_point(m, p.wi, seed, p.stream, walks)
                                          : surface.eval_point(m, p.wi, p.wo, seed, p.stream, walks);
}

std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<TracePoint>& points, Estimator estimator,
                                            std::uint64_t seed, std::int64_t walks, unsigned threads,
                                            const std::function<void(std::uint64_t)>& done) {
    const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
    return util::reduce_blocks(
        points.size(), threads, std::vector<fit::SplitMoments>{},
        [&](std::uint64_t j) {
            return std::vector<fit::SplitMoments>{trace_point(*surface, material, points[j], estimator, seed, walks)};
        },
        [](std::vector<fit::SplitMoments>& all, const std::vector<fit::SplitMoments>& one) {
            all.insert(all.end(), one.begin(), one.end());
        },
        [&](std::uint64_t k) {
            if (done) done(k);
        });
}

}  // namespace smithlab::fitrun
