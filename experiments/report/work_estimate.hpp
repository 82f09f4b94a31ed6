// The size of a report scene's work, estimated from the scene alone before anything is computed, and the limit
// that refuses a scene too large to finish (a 3000 x 3000 x 100 grid would otherwise compute for minutes and end
// in bad_alloc). The unit is one evaluation: a Lambda of a variant at a grid point, a G2 of a G2 variant, a
// reference Lambda, a sample of the sampling experiment, a walk of the walk section at alpha <= 1 (1 to 2.5 events
// on average, 0.1-1 us on one core; nothing of a walk is kept but its cell's sums). Above alpha = 1 a walk counts
// alpha: its length grows like 1.6 alpha events (GGX mirror facets, theta_i = 45: 5 at alpha 3, 16 at 10, 157 at
// 100, 1.6e4 at 1e4), so that a scene of very rough surfaces is refused, not run for hours. It is an upper bound: a
// variant is counted on every NDF of the grid, also those it does not apply to, and every reference is counted as
// computed, also those a cache already holds. Measured (Release, one core): 1e6 Lambda evaluations + 1e6 references
// (schlick-ggx on a 1000 x 1000 GGX grid) take 12 s and 184 MB, ~90 bytes per evaluation kept (grid points, the
// reference cache); so the default limit, 1e8, bounds the report to ~9 GB and tens of minutes, while the default scene
// (1.2e7, nearly all of it the sampling experiment's samples, which are not kept) and the tests' scenes (< 1e6) are far
// inside. The figures pareto and error_maps draw every Lambda evaluation in Python, at ~700 bytes a point: keep a scene
// that draws them near 1e7.
#pragma once

#include <string>
#include <vector>

#include "smithlab/variants.hpp"

namespace smithlab::report {

struct Scene;

inline constexpr double default_max_work = 1e8;

// The work as its parts, each counted by the sections (section.hpp: add_work), in the order first named:
// "Lambda" (selected variants x NDFs of the grid x mu), "references" (reference Lambdas: per grid point one per
// route, at most 3, and the G2 table's), "G2" (selected G2 variants x families x alpha x mu_i x mu_o), "samples"
// (sampling: families x alpha x strategies x samples), "walks" (NDFs x alpha x materials x theta_i x walks x
// max(1, alpha)).
struct Work {
    struct Part {
        std::string name;
        double count = 0.0;
        bool shown_when_zero = true;  // a part that is not, is left out of the message while it is 0
    };
    std::vector<Part> parts;
    // Adds count to the part of that name, or appends the part.
    void add(const std::string& name, double count, bool shown_when_zero = true);
    double of(const std::string& name) const;  // 0 for a part never named
    double total() const;
};

// Every section's work (scene.sections).
Work estimate_work(const Scene& scene, const VariantRegistry& variants);

// "1.23e+07 evaluations (Lambda 1.1e+05, references 7.3e+03, G2 2.2e+03, samples 1.2e+07)", then ", walks 3.2e+05"
// when the scene traces any.
std::string describe(const Work& work);

// Throws input_error naming the scene (source), the estimate, the limit and how to raise it when the work exceeds
// max_work.
void check_work(const Work& work, double max_work, const std::string& source);

}  // namespace smithlab::report
