// The walk side of `import smithlab` (extension smithlab._walk): the facet materials, one trace cell (albedo by
// hemisphere, order and component) and the eval estimator's f(wi, wo) |cos theta_o| over NumPy arrays. The code of
// `smithlab trace` (one cell: index 0 of the random stream) and `smithlab brdf`, so the same bits for the same seed.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "scene/limits.hpp"
#include "scene/walk_options.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/material_registry.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/util/parallel.hpp"
#include "smithlab/walk/trace.hpp"
#include "trace/capped_walks.hpp"
#include "trace/incidence.hpp"
#include "trace/single_analytic.hpp"

namespace smithlab::python {
namespace {

const char* const hemisphere_names[] = {"reflection", "transmission", "all"};
const char* const order_names[] = {"1", "2", "3", "4+", "all"};
const char* const component_names[] = {"specular", "diffuse", "all"};
constexpr int order_columns = walk::order_bins + 1;  // 1, 2, 3, 4+, all

// The viewer's direction in degrees, anywhere (theta > 90: below the surface).
Vec3 outgoing(double theta, double phi) {
    require(theta >= 0.0 && theta <= 180.0, "theta_o", "in [0, 180] degrees", theta);
    require(std::isfinite(phi), "phi_o", "finite", phi);
    return direction_from_deg(theta, phi);
}

// The walk's options by their names (scene/walk_options.hpp), a bad one named as the keyword argument.
walk::MicrosurfaceOptions walk_options(const std::string& downward, const std::string& hit_normal) {
    if (!find_named(downward_names, downward))
        throw input_error("downward must be " + scene::quoted_names(downward_names) + ", got '" + downward + "'");
    if (!find_named(scene::hit_normal_names, hit_normal))
        throw input_error("hit_normal must be " + scene::quoted_names(scene::hit_normal_names) + ", got '" +
                          hit_normal + "'");
    return scene::parse_walk_options(downward, hit_normal, "");
}

// walks in all (walks x pairs for brdf) at most max_walks, as the command line's --max-walks bounds a scene.
void require_walks_threads(long long walks, double all, double max_walks, int threads) {
    require(walks > 0, "walks", "> 0", static_cast<double>(walks));
    require(!std::isnan(max_walks) && max_walks > 0.0, "max_walks", "> 0 (inf: no limit)", max_walks);
    if (all > max_walks)
        throw input_error("walks: " + format_shortest(all) + " walks in all, more than max_walks " +
                          format_shortest(max_walks) + " (raise it with max_walks=N)");
    require(threads >= 0, "threads", ">= 0 (0: all cores)", threads);
}

// ---- trace ------------------------------------------------------------------------------------------------------

struct TraceRequest {
    walk::Material material;
    walk::CellRequest cell;
    walk::MicrosurfaceOptions options;
};

// The cell `smithlab trace --ndf ... --material M --theta-i T --phi-i P --walks N --seed S` traces: the only cell of
// its scene, index 0 (its random stream), walks in blocks of 4096 merged in block order; Ctrl-C honoured between
// blocks.
walk::AlbedoTally trace_cell(const AnyNdf& ndf, const TraceRequest& t, const SignalPoll& poll) {
    const std::shared_ptr<const AnySurface> surface = make_surface(ndf, t.options);
    walk::CellPartial total = util::reduce_blocks(
        walk::block_count(t.cell.walks, t.cell.block), t.cell.threads, walk::empty_partial(t.cell),
        [&](std::uint64_t b) {
            poll();
            return surface->trace_block(t.material, t.cell, b);
        },
        walk::merge_partial, [](std::uint64_t) {});
    return std::move(total.albedo);
}

// Walks cut short (trace/capped_walks.hpp): refused where they could carry more than the albedo's standard error, as
// `smithlab trace` refuses them, else a RuntimeWarning.
void answer_capped(const walk::AlbedoTally& a) {
    if (a.capped == 0) return;
    const walk::Estimate total = a.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    if (trace::capped_beyond_error(a.capped, a.walks, total.stderr_))
        throw input_error("trace: " + trace::capped_text(a.capped, a.walks) +
                          "; the energy they would have carried out (up to " +
                          format_shortest(static_cast<double>(a.capped) / static_cast<double>(a.walks)) +
                          " of the albedo) could exceed the albedo's standard error (" +
                          format_shortest(total.stderr_) + "), so it is no estimate");
    const std::string note = "trace: " + trace::capped_text(a.capped, a.walks) + ", within the albedo's standard error";
    if (PyErr_WarnEx(PyExc_RuntimeWarning, note.c_str(), 1) != 0) throw py::error_already_set();
}

// albedo.csv's numbers of the cell as arrays [hemisphere][order][component] (trace/trace_rows.hpp's order).
py::dict albedo_arrays(const walk::AlbedoTally& a) {
    const std::vector<py::ssize_t> shape{3, order_columns, 3};
    py::array_t<double> albedo(shape), stderr_(shape);
    double* v = albedo.mutable_data();
    double* s = stderr_.mutable_data();
    for (int h = 0; h < 3; ++h)
        for (int o = 0; o < order_columns; ++o)
            for (int c = 0; c < 3; ++c, ++v, ++s) {
                const int order = o == walk::order_bins ? walk::all_orders : o;
                const walk::Estimate e =
                    a.albedo(static_cast<walk::Hemisphere>(h), order, static_cast<walk::Component>(c));
                *v = e.value, *s = e.stderr_;
            }
    py::dict out;
    out["albedo"] = albedo, out["stderr"] = stderr_;
    out["hemispheres"] = std::vector<std::string>(std::begin(hemisphere_names), std::end(hemisphere_names));
    out["orders"] = std::vector<std::string>(std::begin(order_names), std::end(order_names));
    out["components"] = std::vector<std::string>(std::begin(component_names), std::end(component_names));
    return out;
}

// The module's facet materials: the built-in ones (material_registry.hpp).
const MaterialRegistry& materials() {
    static const MaterialRegistry registry;
    return registry;
}

py::dict trace_one_cell(const AnyNdf& ndf, const std::string& material, double theta_i, double phi_i, long long walks,
                        const py::object& seed, int threads, int max_order, const std::string& downward,
                        const std::string& hit_normal, double max_walks) {
    TraceRequest t{materials().make(material), {}, walk_options(downward, hit_normal)};
    require_walks_threads(walks, static_cast<double>(walks), max_walks, threads);
    require(max_order >= 0, "max_order", ">= 0 (0: no limit)", max_order);
    t.cell.wi = trace::incident_direction(theta_i, phi_i, "theta_i", "phi_i", t.material);
    t.cell.seed = seed_of(seed);
    t.cell.cell = 0;
    t.cell.walks = walks;
    t.cell.limits.max_order = max_order;
    t.cell.threads = static_cast<unsigned>(threads);
    walk::AlbedoTally a;
    {
        const SignalPoll poll;
        py::gil_scoped_release free;
        a = trace_cell(ndf, t, poll);
    }
    answer_capped(a);
    py::dict out = albedo_arrays(a);
    out["walks"] = a.walks, out["capped"] = a.capped, out["bounces"] = a.events;
    return out;
}

const char* const trace_doc =
    R"(Traces one cell of the Smith microsurface (Heitz et al. 2016's random walk): `walks` walks
from the incident direction (theta_i, phi_i) in degrees (theta_i in [0, 90); a dielectric also takes (90, 180],
light from below) on facets of `material` (smithlab.materials(); a spec, e.g. 'conductor(eta=0.2, k=3)').

Returns a dict: 'albedo' and 'stderr', float64 arrays of shape (3, 5, 3) indexed by 'hemispheres' (reflection,
transmission, all), 'orders' (1, 2, 3, 4+: the walk left after exactly that many facet hits or more; all) and
'components' (specular: every event a facet reflection; diffuse: any diffuse event; all): the energy leaving into
each selection per unit incident energy (dimensionless) and its standard error; 'walks', 'capped' (walks cut short
at the cap of facet events: refused with ValueError where they could exceed the albedo's standard error, else a
RuntimeWarning) and 'bounces' (facet events in all).
The same bits as `smithlab trace --ndf SPEC --material M --theta-i T --phi-i P --walks N --seed S` (its albedo.csv):
walk k draws from a counter-based generator keyed by (seed, cell 0, k), so any `threads` (0: all cores) gives the
same numbers. max_order = N ends every walk after N hits; downward ('smith' or 'hammon') and hit_normal ('visible'
or 'hammon') as trace's --downward and --hit-normal. More walks than max_walks (as trace's --max-walks; inf: no
limit) raise ValueError. Runs without the GIL; Ctrl-C raises KeyboardInterrupt within a block of walks.)";

// ---- brdf -------------------------------------------------------------------------------------------------------

// What a brdf call holds for every pair.
struct EvalSetup {
    const AnyNdf& ndf;
    walk::Material material;
    std::shared_ptr<const AnySurface> surface;
    walk::EvalRequest request;  // seed, walks, threads; wi and wo set per pair
};

// The numbers `smithlab brdf` prints for one pair, in its order: value, stderr, order_1 .. order_4+ (value and
// stderr each), single_analytic where the facets have one.
struct BrdfNumbers {
    walk::Estimate total;
    std::array<walk::Estimate, walk::order_bins> orders;
    double single = 0.0;
};

// One pair, as run_brdf: refused where the BSDF is a Dirac delta or a walk was cut short; a number that is not
// finite on accepted input is an internal error (RuntimeError), never returned.
BrdfNumbers eval_pair(EvalSetup& s, const Vec3& wi, const Vec3& wo, bool single) {
    s.request.wi = wi, s.request.wo = wo;
    if (s.material.dirac_at(wi, wo))
        throw input_error("brdf: '" + s.material.spec() +
                          "' facets are index-matched (eta = 1): the BSDF is a Dirac delta at wo = -wi, which has no "
                          "finite density to estimate (every other wo gives 0)");
    const walk::EvalTally t = s.surface->eval_cell(s.material, s.request);
    if (t.capped > 0)
        throw input_error("brdf: " + trace::capped_text(t.capped, t.walks) +
                          "; the eval estimator cannot bound what they would still have added, so there is no "
                          "estimate");
    BrdfNumbers n{t.value(), {}, single ? trace::single_analytic(s.ndf, s.material, wi, wo) : 0.0};
    for (int o = 0; o < walk::order_bins; ++o) n.orders[o] = t.value(o, walk::Component::all);
    bool finite = std::isfinite(n.total.value) && std::isfinite(n.total.stderr_) && std::isfinite(n.single);
    for (const walk::Estimate& e : n.orders) finite = finite && std::isfinite(e.value) && std::isfinite(e.stderr_);
    if (!finite) throw std::runtime_error("brdf: a value that is not a finite number on accepted input");
    return n;
}

// The outputs over the broadcast shape: value and stderr, the orders' values and errors (a last axis of 4) and
// single_analytic (filled only where with_single).
struct BrdfArrays {
    py::array_t<double> value, stderr_, order, order_stderr, single;
    bool with_single;
    BrdfArrays(const std::vector<py::ssize_t>& shape, bool with) : value(shape), stderr_(shape), with_single(with) {
        std::vector<py::ssize_t> by_order = shape;
        by_order.push_back(walk::order_bins);
        order = py::array_t<double>(by_order), order_stderr = py::array_t<double>(by_order);
        if (with_single) single = py::array_t<double>(shape);
    }
};

// Every pair of the broadcast angles, one after another, on the GIL-free side: nothing here touches Python.
void eval_pairs(EvalSetup& s, const Broadcast<4>& a, BrdfArrays& out, const walk::MicrosurfaceOptions& options) {
    double* value = out.value.mutable_data();
    double* err = out.stderr_.mutable_data();
    double* order = out.order.mutable_data();
    double* order_err = out.order_stderr.mutable_data();
    double* single = out.with_single ? out.single.mutable_data() : nullptr;
    const SignalPoll poll;
    s.request.before_block = [&poll] { poll(); };
    py::gil_scoped_release free;
    s.surface = make_surface(s.ndf, options);
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Vec3 wi = trace::incident_direction(a.at(0, i), a.at(1, i), "theta_i", "phi_i", s.material);
        const BrdfNumbers n = eval_pair(s, wi, outgoing(a.at(2, i), a.at(3, i)), single != nullptr);
        value[i] = n.total.value;
        err[i] = n.total.stderr_;
        for (int o = 0; o < walk::order_bins; ++o) {
            order[i * walk::order_bins + o] = n.orders[o].value;
            order_err[i * walk::order_bins + o] = n.orders[o].stderr_;
        }
        if (single) single[i] = n.single;
    }
}

// The dict brdf returns: Python floats for value, stderr and single_analytic where every angle was a scalar.
py::dict brdf_result(const Broadcast<4>& a, const BrdfArrays& out) {
    auto result = [&a](const py::array_t<double>& x) -> py::object {
        return a.scalar() ? py::object(py::float_(x.data()[0])) : py::object(x);
    };
    py::dict d;
    d["value"] = result(out.value);
    d["stderr"] = result(out.stderr_);
    d["order"] = out.order;
    d["order_stderr"] = out.order_stderr;
    if (out.with_single) d["single_analytic"] = result(out.single);
    return d;
}

py::dict brdf_pairs(const AnyNdf& ndf, const std::string& material, const py::object& theta_i, const py::object& phi_i,
                    const py::object& theta_o, const py::object& phi_o, long long walks, const py::object& seed,
                    int threads, const std::string& downward, const std::string& estimator, double max_walks) {
    EvalSetup s{ndf, materials().make(material), nullptr, {}};
    const walk::MicrosurfaceOptions options = walk_options(downward, "visible");
    const Named<walk::EvalEstimator>* e = find_named(walk::eval_estimator_names, estimator);
    if (!e)
        throw input_error("estimator must be " + scene::quoted_names(walk::eval_estimator_names) + ", got '" +
                          estimator + "'");
    s.request.estimator = e->value;
    s.request.seed = seed_of(seed), s.request.walks = walks, s.request.threads = static_cast<unsigned>(threads);
    const Broadcast<4> a({theta_i, phi_i, theta_o, phi_o});
    require_walks_threads(walks, static_cast<double>(walks) * static_cast<double>(a.size()), max_walks, threads);
    bool light_below = false;
    for (std::size_t i = 0; i < a.size(); ++i) light_below = light_below || a.at(0, i) > 90.0;
    BrdfArrays out(a.shape(), trace::has_single_analytic(s.material, light_below));
    eval_pairs(s, a, out, options);
    return brdf_result(a, out);
}

const char* const brdf_doc = R"(f(wi, wo) |cos theta_o| of the Smith microsurface (1/sr) by the eval estimator
(next-event estimation toward wo at every hit; estimator: 'next_event', 'expected_first', 'reciprocal' or
'position_free', as brdf's --estimator, all unbiased), over the four angle arguments in degrees broadcast against each other
(NumPy's rules): the light at (theta_i, phi_i), theta_i in [0, 90) (a dielectric also takes (90, 180], light from
below), the viewer at (theta_o, phi_o), theta_o in [0, 180] (above 90: transmission, for a dielectric).

Returns a dict: 'value' and 'stderr' (the broadcast shape; Python floats when every angle is a scalar), 'order' and
'order_stderr' (that shape plus a last axis of 4: the walks' light after 1, 2, 3 and 4 or more facet hits), and, for
mirror and conductor facets (and dielectric facets when every theta_i < 90), 'single_analytic': the
single-scattering BSDF times |cos theta_o| (Walter 2007 eq. 20 and 21 with the height-correlated G2).
Each pair is the same bits as `smithlab brdf --ndf SPEC --material M --wi T,P --wo T,P --walks N --seed S`; its
walks run on `threads` threads (0: all cores), the pairs one after another (and --estimator E for estimator=E). More walks in all (walks x pairs) than
max_walks (inf: no limit) raise ValueError. Runs without the GIL; Ctrl-C raises KeyboardInterrupt within a block of
walks.)";

}  // namespace

void bind_walk(py::module_& m) {
    m.def(
        "materials",
        [] {
            std::vector<std::pair<std::string, std::string>> out;
            for (const walk::MaterialInfo* m : materials().list())
                out.emplace_back(m->name, m->spec() + ": " + m->description);
            return out;
        },
        "The facet materials of the walk (as `smithlab trace --help` lists them): (name, description) pairs; the "
        "description opens with the spec and its defaults, e.g. 'lambert(albedo=1)'.");
    m.def("trace", &trace_one_cell, py::arg("ndf"), py::arg("material") = "mirror", py::arg("theta_i") = 45.0,
          py::arg("phi_i") = 0.0, py::arg("walks") = 1'000'000, py::arg("seed") = 1, py::arg("threads") = 0,
          py::arg("max_order") = 0, py::arg("downward") = "smith", py::arg("hit_normal") = "visible",
          py::arg("max_walks") = scene::SizeLimits{}.max_walks, trace_doc);
    m.def("brdf", &brdf_pairs, py::arg("ndf"), py::arg("material"), py::arg("theta_i"), py::arg("phi_i"),
          py::arg("theta_o"), py::arg("phi_o"), py::arg("walks") = 1'000'000, py::arg("seed") = 1,
          py::arg("threads") = 0, py::arg("downward") = "smith", py::arg("estimator") = "next_event",
          py::arg("max_walks") = scene::SizeLimits{}.max_walks, brdf_doc);
}

}  // namespace smithlab::python
