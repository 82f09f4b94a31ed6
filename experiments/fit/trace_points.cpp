#include "fit/trace_points.hpp"

#include <cstdio>
#include <memory>

#include "smithlab/util/parallel.hpp"
#include "trace/capped_walks.hpp"

namespace smithlab::fit {

fit::SplitMoments trace_point(const AnySurface& surface, const walk::Material& m, const TracePoint& p,
                              Estimator estimator, std::uint64_t seed, std::int64_t walks) {
    return estimator.albedo ? surface.albedo_point(m, p.wi, seed, p.stream, walks)
                            : surface.eval_point(m, p.wi, p.wo, seed, p.stream, walks, estimator.eval);
}

std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<TracePoint>& points, Estimator estimator,
                                            std::uint64_t seed, std::int64_t walks, unsigned threads,
                                            const std::function<void(std::uint64_t)>& done) {
    const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
    std::vector<fit::SplitMoments> traced = util::reduce_blocks(
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
    std::int64_t capped = 0;
    for (const fit::SplitMoments& m : traced) capped += m.capped;
    if (capped > 0)
        std::fprintf(stderr, "fit: warning: %s (%s, %s): their energy is missing from the values drawn\n",
                     trace::capped_text(capped, walks * static_cast<std::int64_t>(points.size())).c_str(),
                     ndf.spec().c_str(), material.spec().c_str());
    return traced;
}

}  // namespace smithlab::fit
