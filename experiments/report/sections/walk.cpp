// The walk as a report section (walk_section.hpp): the scene's [walk] (materials, alpha, theta_i, walks, seed, and
// its [[walk.ndf]] tables). Traced by every MPI rank together. Without it, nothing (no walks in the work's message).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "cluster/mpi_world.hpp"
#include "report/sections.hpp"
#include "report/walk_section.hpp"
#include "scene/limits.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/walk/facets.hpp"

namespace smithlab::report {

namespace {

void read_materials(scene::StrictTable& w, WalkScene& walk, const MaterialRegistry& materials) {
    walk.materials = w.texts("materials", walk.materials);
    if (walk.materials.empty()) w.fail("materials", "is an empty list");
    for (const std::string& m : walk.materials) try {
            materials.make(m);
        } catch (const input_error& e) {
            w.fail("materials", "holds \"" + m + "\": " + e.what());
        }
}

void read_axes(scene::StrictTable& w, WalkScene& walk) {
    walk.alphas = scene::read_axis(w, "alpha");
    for (double a : walk.alphas)
        if (!std::isfinite(a)) w.fail("alpha", "must be finite, got " + format_shortest(a));
    if (w.has("theta_i")) walk.theta_i = scene::read_axis(w, "theta_i");
    for (double t : walk.theta_i)
        if (!(t >= 0.0 && t < 90.0))
            w.fail("theta_i", "must be in [0, 90) degrees (light from above), got " + format_shortest(t));
}

class WalkSection : public Section {
public:
    std::vector<std::string> keys() const override { return {"walk"}; }

    void read(scene::StrictTable& doc, const Settings& settings, const NdfRegistry& registry) override {
        auto w = doc.optional_table("walk", {"ndf", "materials", "alpha", "theta_i", "walks", "seed"});
        if (!w) return;
        for (scene::StrictTable& n : w->tables("ndf", scene::ndf_table_keys(registry))) {
            scene_.ndfs.push_back(scene::read_ndf_entry(n, registry));
            n.done();
        }
        if (scene_.ndfs.empty()) w->fail("ndf", "is missing: no [[walk.ndf]] table names an NDF family");
        read_materials(*w, scene_, registry.materials());
        read_axes(*w, scene_);
        scene_.walks = scene::scaled_count(w->integer("walks", 100, 1'000'000'000, scene_.walks), settings.scale, 100);
        scene_.seed = static_cast<unsigned long long>(w->integer("seed", 0, INT64_MAX, 1));
        w->done();
    }

    // walks: NDFs x alpha x materials x theta_i x walks, a walk above alpha = 1 counted alpha times (its length grows
    // like alpha); shown only when the scene traces any.
    void add_work(Work& work, const Settings&, const VariantRegistry&) const override {
        double ndfs = 0.0, alphas = 0.0;
        for (const scene::NdfEntry& e : scene_.ndfs) ndfs += static_cast<double>(e.count(1));
        for (double a : scene_.alphas) alphas += std::max(1.0, a);
        work.add("walks",
                 ndfs * alphas * static_cast<double>(scene_.materials.size() * scene_.theta_i.size()) *
                     static_cast<double>(scene_.walks),
                 false);
    }

    void check(const Settings&, const NdfRegistry& ndfs, const VariantRegistry&) override {
        cells_ = walk_cells(scene_, ndfs);
    }

    bool on_all_ranks() const override { return true; }

    void compute() override {
        if (cells_.empty()) return;
        if (cluster::mpi::rank() == 0)
            std::fprintf(stderr, "report: walk section, %zu cells of %lld walks\n", cells_.size(),
                         static_cast<long long>(scene_.walks));
        const auto t0 = std::chrono::steady_clock::now();
        results_ = trace_walk_cells(cells_, scene_);
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    void write(const std::filesystem::path& dir, const Settings&) override {
        if (!results_.empty()) write_walk_section(results_, scene_, seconds_, dir);
    }

    bool draws(const Settings&) const override { return !scene_.ndfs.empty(); }

private:
    WalkScene scene_;
    std::vector<WalkCell> cells_;
    std::vector<WalkResult> results_;  // rank 0's
    double seconds_ = 0.0;
};

}  // namespace

std::unique_ptr<Section> walk_section() { return std::make_unique<WalkSection>(); }

}  // namespace smithlab::report
