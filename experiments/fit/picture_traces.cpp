#include "fit/picture_traces.hpp"

#include <chrono>
#include <cstdio>
#include <optional>

#include "fit/point_cache.hpp"
#include "fit/trace_points.hpp"
#include "output/progress.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

enum PictureSet : std::uint64_t { sphere_set = 3, slice_set = 4, lambert_sphere_set = 5, lambert_albedo_set = 6 };

const char* picture_set_name(PictureSet set) {
    switch (set) {
        case sphere_set:
            return "spheres";
        case slice_set:
            return "slices";
        case lambert_sphere_set:
            return "lambert-spheres";
        case lambert_albedo_set:
            return "lambert-albedo";
    }
    return "";
}

std::uint64_t picture_stream(PictureSet set, std::uint64_t ndf, std::uint64_t group, std::uint64_t point) {
    if (ndf >= (1u << 12) || group >= (1u << 12) || point >= (std::uint64_t{1} << 32))
        throw input_error("fit: pictures: too many NDFs, alphas or pixels for the pictures' random streams");
    return set << 56 | ndf << 44 | group << 32 | point;
}

// One trace: a set of points on one NDF at one alpha, with one material and estimator; its cache file, and its
// moments once read back or traced.
struct Trace {
    std::string what;  // "ggx, alpha 0.25: spheres"
    AnyNdf ndf;
    std::string material;
    Estimator estimator;
    std::int64_t walks;
    std::vector<TracePoint> points;
    CacheFile file;
    std::vector<fit::SplitMoments>* into;
    std::optional<std::vector<fit::SplitMoments>> moments = std::nullopt;
};

// What places one trace in the scene: its NDF (index and label), alpha (index and value) and set.
struct TracePlace {
    std::size_t n;
    const std::string& label;
    std::size_t a;
    double alpha;
    PictureSet set;
};

Trace make_trace(const TracePlace& at, AnyNdf ndf, const std::string& material, const std::vector<Pair>& pairs,
                 std::int64_t walks, const PictureSpec& s, const fs::path& cache,
                 std::vector<fit::SplitMoments>* into) {
    const std::string set = picture_set_name(at.set);
    Trace t{at.label + ", alpha " + format_shortest(at.alpha) + ": " + set,
            std::move(ndf),
            material,
            Estimator{at.set == lambert_albedo_set, s.estimator},
            walks,
            {},
            {},
            into};
    t.file = {cache / cache_directory_name(at.label) / "pictures" / (set + "-" + std::to_string(at.a) + ".csv"),
              cache_key(t.ndf, material, set, walks, s.seed, picture_stream(at.set, at.n, at.a, 0), pairs.size(),
                        s.estimator),
              {"wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z"},
              {},
              walks};
    for (std::size_t j = 0; j < pairs.size(); ++j) {
        const Pair& p = pairs[j];
        t.points.push_back({p.wi, p.wo, picture_stream(at.set, at.n, at.a, j)});
        t.file.points.push_back({format_g17(p.wi.x()), format_g17(p.wi.y()), format_g17(p.wi.z()), format_g17(p.wo.x()),
                                 format_g17(p.wo.y()), format_g17(p.wo.z())});
    }
    return t;
}

// Every trace of the pictures, in the scene's order, each writing into its place of `out` (sized here).
std::vector<Trace> plan(const PictureSpec& s, const std::vector<NdfData>& data, const SphereGroup& spheres,
                        const std::vector<Pair>& slices, const NdfRegistry& registry, const fs::path& cache,
                        std::vector<PictureData>& out) {
    const std::string lambert = "lambert(albedo=1)";
    const FitScene::Pictures& p = s.pictures;
    std::vector<Pair> albedo_points;
    for (double t : missing_theta) albedo_points.push_back({direction_from_theta_deg(t), Vec3(0.0, 0.0, 1.0)});
    out.assign(data.size(), {});
    std::vector<Trace> traces;
    for (std::size_t n = 0; n < data.size(); ++n) {
        PictureData& o = out[n];
        o.spheres.resize(p.sphere_alpha.size());
        o.lambert_spheres.resize(p.sphere_alpha.size());
        o.lambert_albedo.resize(p.sphere_alpha.size());
        o.slices.resize(p.slice_alpha.size());
        const std::string& label = data[n].label;
        for (std::size_t a = 0; a < p.sphere_alpha.size(); ++a) {
            const double alpha = p.sphere_alpha[a];
            const AnyNdf ndf = make_ndf(registry, data[n].family, alpha);
            traces.push_back(make_trace({n, label, a, alpha, sphere_set}, ndf, s.material, spheres.traced, p.walks, s,
                                        cache, &o.spheres[a]));
            traces.push_back(make_trace({n, label, a, alpha, lambert_sphere_set}, ndf, lambert, spheres.traced, p.walks,
                                        s, cache, &o.lambert_spheres[a]));
            traces.push_back(make_trace({n, label, a, alpha, lambert_albedo_set}, ndf, lambert, albedo_points,
                                        missing_walks, s, cache, &o.lambert_albedo[a]));
        }
        for (std::size_t a = 0; a < p.slice_alpha.size(); ++a) {
            const double alpha = p.slice_alpha[a];
            traces.push_back(make_trace({n, label, a, alpha, slice_set}, make_ndf(registry, data[n].family, alpha),
                                        s.material, slices, p.walks, s, cache, &o.slices[a]));
        }
    }
    return traces;
}

// Walks traced of walks to trace, for the progress line.
struct Progress {
    output::ProgressLine line;
    std::int64_t done = 0, total = 0;
    void report(std::int64_t now_done) {
        line(static_cast<double>(now_done) / static_cast<double>(total), [&] {
            return "fit: pictures: traced " + std::to_string(now_done / 1000000) + " of " +
                std::to_string(total / 1000000) + " walks (millions)";
        });
    }
};

void run(Trace& t, const MaterialRegistry& materials, std::uint64_t seed, unsigned threads, Progress& progress) {
    std::fprintf(stderr, "fit: pictures: %s\n", t.what.c_str());
    const std::int64_t before = progress.done;
    t.moments =
        trace_points(t.ndf, materials.make(t.material), t.points, t.estimator, seed, t.walks, threads,
                     [&](std::uint64_t k) { progress.report(before + static_cast<std::int64_t>(k) * t.walks); });
    progress.done += static_cast<std::int64_t>(t.points.size()) * t.walks;
    write_cache(t.file, *t.moments);
}

}  // namespace

std::vector<PictureData> trace_pictures(const PictureSpec& s, const std::vector<NdfData>& data,
                                        const SphereGroup& spheres, const std::vector<Pair>& slices,
                                        const NdfRegistry& registry, const fs::path& cache, unsigned threads,
                                        std::int64_t& walks_traced) {
    std::vector<PictureData> out;
    std::vector<Trace> traces = plan(s, data, spheres, slices, registry, cache, out);
    Progress progress;
    std::size_t cached = 0;
    for (Trace& t : traces) {
        t.moments = read_cache(t.file);
        if (t.moments) ++cached;
        else progress.total += static_cast<std::int64_t>(t.points.size()) * t.walks;
    }
    if (cached) std::fprintf(stderr, "fit: pictures: %zu of %zu traces read from the cache\n", cached, traces.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (Trace& t : traces) {
        if (!t.moments) run(t, registry.materials(), s.seed, threads, progress);
        *t.into = std::move(*t.moments);
    }
    if (progress.total)
        std::fprintf(stderr, "fit: pictures: traced %.1f million walks in %.1f s\n",
                     static_cast<double>(progress.total) / 1e6,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    walks_traced = progress.total;
    return out;
}

}  // namespace smithlab::fit
