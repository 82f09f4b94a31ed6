// The NDF side of `import smithlab` (extension smithlab._ndf): NDFs by spec or by parameters, their D, P22, P2,
// Lambda, G1 and G2 over NumPy arrays by every method `smithlab eval` has (the same code: evaluation/route.hpp, so
// the same bits), the GTR family's stream, a measured D as an NDF, and the samplers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "evaluation/route.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/gtr/family_stream.hpp"
#include "smithlab/gtr/registry.hpp"
#include "smithlab/samplers.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/tabulated.hpp"

namespace smithlab::python {
namespace {

// The module's NDFs: the built-in ones, and the measured tables made in this process (tabulated()), by name: a name
// made again (a notebook cell run twice) takes the new table, which later ndf(name) calls build from.
struct Catalogue {
    NdfRegistry registry = builtin_registry();
    VariantRegistry variants = builtin_variants();
    std::map<std::string, TabulatedNdf> tables;
};
Catalogue& catalogue() {
    static Catalogue c;
    return c;
}

void require_tolerance(double tolerance) {
    using evaluation::min_tolerance, evaluation::max_tolerance;
    require(tolerance >= min_tolerance && tolerance <= max_tolerance, "tolerance",
            "in [" + format_shortest(min_tolerance) + ", " + format_shortest(max_tolerance) + "]", tolerance);
}

// A method's route, as `smithlab eval --method M --backend B --tolerance T --downward D` takes it.
evaluation::Prepared prepared(const AnyNdf& ndf, const evaluation::RouteOptions& options) {
    require_tolerance(options.tolerance);
    return evaluation::prepare(ndf, evaluation::route(options, catalogue().variants));
}

AnyNdf make_ndf(const std::string& spec, const py::kwargs& params) {
    if (params.empty()) return catalogue().registry.make(spec);
    const NdfInfo* info = catalogue().registry.find(spec);
    std::vector<std::pair<std::string, double>> values;
    std::vector<std::pair<std::string, std::string>> texts;
    for (const auto& [key, value] : params) {
        const auto name = key.cast<std::string>();
        const bool text = info &&
            std::find(info->text_parameters.begin(), info->text_parameters.end(), name) != info->text_parameters.end();
        const auto refuse = [&] {
            return input_error(spec + ": " + name + " takes " + (text ? "text" : "a number") + ", got " +
                               py::repr(value).cast<std::string>());
        };
        if (text != py::isinstance<py::str>(value)) throw refuse();
        if (text) {
            texts.emplace_back(name, value.cast<std::string>());
            continue;
        }
        try {
            values.emplace_back(name, value.cast<double>());
        } catch (const py::cast_error&) {
            throw refuse();
        }
    }
    return catalogue().registry.make(spec, values, texts);
}

double require_number(double x, const char* what) {
    require(!std::isnan(x), what, "a number", x);
    return x;
}

// P2(q) by quadrature; 0 at q = +-inf (its limit: P22 falls at least like r^-3 in every accepted NDF).
double P2_at(const AnyNdf& n, double q, const QuadratureOptions& o) {
    return std::isinf(require_number(q, "q")) ? 0.0 : smithlab::P2(n, q, o);
}

// A measured D (one of cos_theta, theta_deg, with D) as the NDF family `name` (parameter scale, as the registry's
// tabulated: a roughness alpha sets it), registered in the module's catalogue; the table is read as tabulated.hpp
// reads a CSV file, with every refusal of that reading.
AnyNdf tabulated(const std::string& name, const py::object& cos_theta, const py::object& theta_deg, const py::object& D,
                 bool normalize) {
    if (cos_theta.is_none() == theta_deg.is_none())
        throw input_error("tabulated '" + name + "': give exactly one of cos_theta and theta_deg");
    const bool by_cos = !cos_theta.is_none();
    const Array x(by_cos ? cos_theta : theta_deg), d(D);
    if (x.ndim() != 1 || d.ndim() != 1 || x.size() != d.size())
        throw input_error("tabulated '" + name + "': " + (by_cos ? "cos_theta" : "theta_deg") +
                          " and D must be 1-D arrays of one length, got shapes " + shape_text(x) + " and " +
                          shape_text(d));
    const bool made_here = catalogue().tables.count(name) > 0;
    if (catalogue().registry.find(name) && !made_here)
        throw input_error("tabulated: the name '" + name + "' is taken (smithlab.list() names every NDF)");
    std::string text = by_cos ? "cos_theta,D\n" : "theta_deg,D\n";
    for (py::ssize_t i = 0; i < x.size(); ++i) text += format_g17(x.data()[i]) + "," + format_g17(d.data()[i]) + "\n";
    // The table is read once here: its refusals (rows out of order, a negative D, an area far from 1) come now,
    // naming the row ("NAME:LINE: ..."; line 2 is the first value).
    catalogue().tables.insert_or_assign(name, tabulated_ndf_from_csv(text, name, {.normalize = normalize}));
    if (!made_here) {
        // the family builds from the name's current table
        auto table = [name] { return catalogue().tables.at(name); };
        catalogue().registry.add(
            {.name = name,
             .parameters = {"scale"},
             .description = "a measured D(theta_m) given from Python, interpolated (tabulated.hpp); scale stretches "
                            "its slopes (default 1)",
             .examples = {},
             .roughness =
                 NdfInfo::Roughness{
                     "scale", [table](double alpha, const NdfParams&) { return alpha / core_slope_scale(table()); }},
             .defaults = {{"scale", 1.0}}},
            [table](const NdfParams& p) { return table().scaled(p.at("scale")); });
    }
    return catalogue().registry.make(name, {});
}

// Ndf.Lambda, G1 and G2: their values at every element of the broadcast arguments, by the route of their method (the
// downward convention Lambda's argument; smith for G1 and G2, which take |mu|).
py::object ndf_Lambda(const AnyNdf& n, const py::object& mu, const std::string& method, const std::string& backend,
                      double tolerance, const std::string& downward) {
    const evaluation::Prepared p = prepared(n, {method, backend, downward, tolerance});
    const Downward d = parse_downward(downward);
    return elementwise<1>([&](double x) { return evaluation::lambda_g1(p, x, d).lambda; }, {mu});
}

py::object ndf_G1(const AnyNdf& n, const py::object& mu, const std::string& method, const std::string& backend,
                  double tolerance) {
    const evaluation::Prepared p = prepared(n, {method, backend, "smith", tolerance});
    return elementwise<1>([&](double x) { return evaluation::lambda_g1(p, x, Downward::smith).g1; }, {mu});
}

py::object ndf_G2(const AnyNdf& n, const py::object& mu_i, const py::object& mu_o, const std::string& form,
                  const std::string& method, const std::string& backend, double tolerance) {
    G2Form f;
    if (form == "height-correlated") f = G2Form::height_correlated;
    else if (form == "uncorrelated") f = G2Form::uncorrelated;
    else throw input_error("G2: form must be 'height-correlated' or 'uncorrelated', got '" + form + "'");
    const evaluation::Prepared p = prepared(n, {method, backend, "smith", tolerance});
    return elementwise<2>(
        [&](double a, double b) {
            require_mu_number(a);
            require_mu_number(b);
            return G2_from_Lambdas(Lambda_of_abs(a, p.Lambda_up), Lambda_of_abs(b, p.Lambda_up),
                                   (a >= 0.0) == (b >= 0.0), f);
        },
        {mu_i, mu_o});
}

// The registered NDFs as dicts, for smithlab.list().
py::list ndf_list() {
    py::list out;
    for (const NdfInfo* i : catalogue().registry.list()) {
        py::dict d;
        d["name"] = i->name, d["parameters"] = i->parameters, d["description"] = i->description,
        d["examples"] = i->examples;
        out.append(d);
    }
    return out;
}

// The GTR family's stream over broadcast arrays, a part of its inputs at a time without the GIL.
py::object family_G1(const py::object& alpha, const py::object& gamma, const py::object& mu) {
    Broadcast<3> b(std::array<py::object, 3>{alpha, gamma, mu});
    {
        py::gil_scoped_release free;
        constexpr std::size_t part = 4096;  // the stream's inputs a part at a time: a scalar is never spread
        std::array<std::array<double, part>, 3> buffer;
        for (std::size_t first = 0; first < b.size(); first += part) {
            const std::size_t n = std::min(part, b.size() - first);
            auto in = [&](std::size_t k) { return std::span(b.part(k, first, n, buffer[k].data()), n); };
            G1_gtr_family(in(0), in(1), in(2), std::span(b.output() + first, n), first);
        }
    }
    return b.result();
}

// n normals by the named sampler, for smithlab.sample(): (normals (n, 3), pdf (n,)).
py::tuple sample_normals(const AnyNdf& n, const std::string& sampler, long long count, double theta_i,
                         const py::object& seed) {
    require(count >= 0, "n", ">= 0", static_cast<double>(count));
    require(theta_i >= 0.0 && theta_i < 180.0, "theta_i", "in [0, 180) degrees", theta_i);
    const std::uint64_t s = seed_of(seed);
    const std::vector<SamplerInfo> all = builtin_samplers();
    const BoundSampler b = prepare(find_sampler(all, sampler), n, direction_from_theta_deg(theta_i));
    py::array_t<double> normals({static_cast<py::ssize_t>(count), py::ssize_t{3}});
    py::array_t<double> pdf(static_cast<py::ssize_t>(count));
    double* x = normals.mutable_data();
    double* p = pdf.mutable_data();
    {
        py::gil_scoped_release free;
        Rng rng = make_rng(s);
        for (long long i = 0; i < count; ++i) {
            const NormalSample d = b.sample(rng);
            x[3 * i] = d.m.x(), x[3 * i + 1] = d.m.y(), x[3 * i + 2] = d.m.z(), p[i] = d.pdf;
        }
    }
    return py::make_tuple(normals, pdf);
}

const char* const lambda_doc = R"(Smith's Lambda at mu = cot(theta_v) (NumPy array or scalar, broadcast).

mu = 0 is grazing (Lambda = inf), mu = inf the normal (0), mu < 0 a direction below the surface (downward:
'smith', Lambda(-mu) = -1 - Lambda(mu), or 'hammon', -Lambda(mu)). method: 'auto' (the closed form where the NDF
has one, else the fixed rule), 'closed', 'spline', 'quadrature', 'quadrature2d', 'fixed', or any name of
smithlab.methods(); backend ('boost' or 'gsl') and tolerance (relative, in [1e-15, 0.1]) set the quadratures.
The same code and bits as `smithlab eval`. NaN in mu raises ValueError.)";

// The class Ndf: what an NDF is (its spec, family, parameters) and its densities D, P22 and P2.
py::class_<AnyNdf> bind_ndf_class(py::module_& m) {
    py::class_<AnyNdf> ndf(m, "Ndf", "An isotropic NDF: smithlab.ndf('gtr(alpha=0.3, gamma=1.5)').");
    ndf.def_property_readonly("spec", &AnyNdf::spec, "the canonical spec, e.g. 'gtr(alpha=0.3, gamma=1.5)'")
        .def_property_readonly("family", &AnyNdf::family, "the family's name, e.g. 'gtr'")
        .def_property_readonly("note", &AnyNdf::note, "how the NDF was built, where a user should know ('' mostly)")
        .def_property_readonly(
            "params",
            [](const AnyNdf& n) {
                std::map<std::string, double> p;
                for (const auto& [k, v] : n.parts().params) p[k] = v;
                return p;
            },
            "the numeric parameters by name")
        .def_property_readonly("has_closed_Lambda", &AnyNdf::has_closed_Lambda)
        .def("__repr__", [](const AnyNdf& n) { return "smithlab.ndf('" + n.spec() + "')"; })
        .def(
            "D",
            [](const AnyNdf& n, const py::object& c) {
                return elementwise<1>(
                    [&](double x) {
                        require(x >= -1.0 && x <= 1.0, "cos_theta_m", "in [-1, 1]", x);  // NaN too
                        return n.D(x);
                    },
                    {c});
            },
            py::arg("cos_theta_m"),
            "D(theta_m) per steradian of m, normalized: the integral of D cos theta_m over the hemisphere is 1 "
            "(Walter et al. 2007 eq. 4); 0 for cos_theta_m <= 0.")
        .def(
            "P22",
            [](const AnyNdf& n, const py::object& x, const py::object& y) {
                return elementwise<2>(
                    [&](double p, double q) {
                        return n.slope_density(require_number(p, "slope_x") * p + require_number(q, "slope_y") * q);
                    },
                    {x, y});
            },
            py::arg("slope_x"), py::arg("slope_y"),
            "The slope density P22(x, y) = D cos^4 theta_m at tan^2 theta_m = x^2 + y^2 (Walter 2007 eq. 42).")
        .def(
            "P2",
            [](const AnyNdf& n, const py::object& q, const std::string& backend, double tolerance) {
                require_tolerance(tolerance);
                const QuadratureOptions o{parse_backend(backend), tolerance};
                return elementwise<1>([&](double x) { return P2_at(n, x, o); }, {q});
            },
            py::arg("q"), py::arg("backend") = "boost", py::arg("tolerance") = 1e-12,
            "The marginal slope density P2(q), the integral of P22(p, q) over p (Walter 2007 eq. 43), by quadrature.");
    return ndf;
}

// Ndf.Lambda, G1 and G2, by every route `smithlab eval --method` takes.
void bind_smith_functions(py::class_<AnyNdf>& ndf) {
    ndf.def("Lambda", &ndf_Lambda, py::arg("mu"), py::arg("method") = "auto", py::arg("backend") = "boost",
            py::arg("tolerance") = 1e-12, py::arg("downward") = "smith", lambda_doc);
    ndf.def("G1", &ndf_G1, py::arg("mu"), py::arg("method") = "auto", py::arg("backend") = "boost",
            py::arg("tolerance") = 1e-12,
            "Smith's G1 = 1 / (1 + Lambda(|mu|)) (Walter 2007 eq. 44), mu = cot(theta_v); the methods as Lambda's. "
            "Where Lambda overflows (mu > 0 tiny) G1 comes from the grazing law, never 0/0.");
    ndf.def("G2", &ndf_G2, py::arg("mu_i"), py::arg("mu_o"), py::arg("form") = "height-correlated",
            py::arg("method") = "auto", py::arg("backend") = "boost", py::arg("tolerance") = 1e-12,
            "Smith's G2 of two directions mu_i, mu_o = cot(theta) (negative: below): 'height-correlated' "
            "1 / (1 + Lambda_i + Lambda_o) on one side, Beta(1 + Lambda_i, 1 + Lambda_o) across it (Heitz 2014), or "
            "'uncorrelated' G1 G1 (Walter 2007 eq. 23).");
}

// smithlab.ndf, list, methods and tabulated: the NDFs by name, and a measured one added.
void bind_catalogue(py::module_& m) {
    m.def("ndf", &make_ndf, py::arg("spec"),
          "An NDF by spec, ndf('gtr(alpha=0.3, gamma=1.5)'), or by family and parameters, ndf('gtr', alpha=0.3, "
          "gamma=1.5). ValueError names an unknown NDF or parameter and a value out of its domain.");
    m.def("list", &ndf_list,
          "The registered NDFs (as `smithlab list`): dicts of name, parameters, description, examples.");
    m.def(
        "methods", [] { return evaluation::method_list(catalogue().variants); },
        "Every method Lambda, G1 and G2 take (as `smithlab eval --list-methods`): (name, description) pairs.");
    m.def("tabulated", &tabulated, py::arg("name"), py::kw_only(), py::arg("cos_theta") = py::none(),
          py::arg("theta_deg") = py::none(), py::arg("D"), py::arg("normalize") = false,
          "A measured D as a registered NDF (its family `name`, parameter scale): rows by cos_theta (decreasing) or "
          "theta_deg (increasing, [0, 90)), D per steradian normalized to projected area 1 (normalize=True divides "
          "by the area instead of refusing one off by more than 1e-2). Interpolated as tabulated.hpp says; every "
          "derived quantity then runs in C++.");
}

// smithlab.family_G1, samplers and sample.
void bind_family_and_samplers(py::module_& m) {
    m.def("family_G1", &family_G1, py::arg("alpha"), py::arg("gamma"), py::arg("mu"),
          "G1 of GTR(alpha, gamma) at mu = cot(theta), over arrays (broadcast): the family evaluator's stream "
          "(alpha in [1e-4, 1], gamma in [0, 20]; |dG1| within its stated bound, 9.5e-7), AVX2 or AVX-512 where the "
          "CPU has them. ValueError names the first offending item.");
    m.def(
        "samplers",
        [] {
            std::vector<std::pair<std::string, std::string>> out;
            for (const SamplerInfo& s : builtin_samplers()) out.emplace_back(s.name, s.description);
            return out;
        },
        "The samplers of microfacet normals (as `smithlab sample --list-samplers`): (name, description) pairs.");
    m.def("sample", &sample_normals, py::arg("ndf"), py::arg("sampler"), py::arg("n") = 1000, py::arg("theta_i") = 0.0,
          py::arg("seed") = 1,
          "n microfacet normals by a named sampler for the incident direction at theta_i degrees (phi 0): (normals "
          "(n, 3), pdf (n,)), the pdf per steradian of m. The numbers of `smithlab sample` for the same seed.");
}

}  // namespace

void bind_ndfs(py::module_& m) {
    py::class_<AnyNdf> ndf = bind_ndf_class(m);
    bind_smith_functions(ndf);
    bind_catalogue(m);
    bind_family_and_samplers(m);
}

}  // namespace smithlab::python
