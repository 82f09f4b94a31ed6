// The fitter's pieces in `import smithlab` (extension smithlab._walk): the diffuse models (fit/diffuse_models.hpp)
// over NumPy arrays, the constants a `smithlab fit` run wrote (its constants.csv), and the Kulla-Conty compensation
// table of any NDF (compensation/compensation.hpp, the fit's [compensation] route: the same bits).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "smithlab/any_ndf.hpp"
#include "smithlab/compensation/compensation.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/fit/diffuse_models.hpp"

namespace smithlab::python {
namespace {

namespace fs = std::filesystem;

// ---- the diffuse models -----------------------------------------------------------------------------------------

py::list models() {
    py::list out;
    for (const fit::DiffuseModel& m : fit::diffuse_models()) {
        py::dict d;
        d["name"] = std::string(m.name), d["description"] = std::string(m.source);
        d["constants"] = std::vector<std::string>(m.parameters.begin(), m.parameters.end());
        d["published"] = m.published;
        d["glsl"] = m.glsl.get() != nullptr;
        out.append(d);
    }
    return out;
}

std::string constant_names(const fit::DiffuseModel& m) {
    std::string out;
    for (std::string_view p : m.parameters) out += (out.empty() ? "" : ", ") + std::string(p);
    return out.empty() ? "none" : out;
}

// The model's constants: its published ones (None), else a sequence of exactly its count, each finite.
std::vector<double> constants_of(const fit::DiffuseModel& m, const py::object& given) {
    if (given.is_none()) return m.published;
    const std::string name = "diffuse_f: '" + std::string(m.name) + "'";
    std::vector<double> c;
    try {
        c = given.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
        throw input_error(name + ": constants must be None or a sequence of numbers, got " +
                          py::repr(given).cast<std::string>());
    }
    if (c.size() != m.parameters.size())
        throw input_error(name + " takes " + std::to_string(m.parameters.size()) +
                          (m.parameters.size() == 1 ? " constant (" : " constants (") + constant_names(m) + "), got " +
                          std::to_string(c.size()));
    for (std::size_t i = 0; i < c.size(); ++i)
        require(std::isfinite(c[i]), name + " constant " + std::string(m.parameters[i]), "finite", c[i]);
    return c;
}

py::object diffuse_f(const std::string& model, const py::object& theta_i, const py::object& theta_o,
                     const py::object& phi, const py::object& alpha, const py::object& albedo,
                     const py::object& constants) {
    const fit::DiffuseModel& m = fit::find_diffuse_model(model);
    const std::vector<double> c = constants_of(m, constants);
    return elementwise<5>(
        [&](double ti, double to, double p, double a, double rho) {
            require(ti >= 0.0 && ti < 90.0, "theta_i", "in [0, 90) degrees", ti);
            require(to >= 0.0 && to < 90.0, "theta_o", "in [0, 90) degrees", to);
            require(std::isfinite(p), "phi", "finite", p);
            require(a > 0.0 && a <= 1.0, "alpha", "in (0, 1]", a);
            require(rho >= 0.0 && rho <= 1.0, "albedo", "in [0, 1]", rho);
            const double f = m.f(direction_from_deg(ti, 0.0), direction_from_deg(to, p), a, rho, c.data());
            if (std::isnan(f))
                throw input_error("diffuse_f: '" + model + "' is not a number at theta_i " + format_shortest(ti) +
                                  ", theta_o " + format_shortest(to) + ", phi " + format_shortest(p) + ", alpha " +
                                  format_shortest(a) + " with these constants");
            return f;
        },
        {theta_i, theta_o, phi, alpha, albedo});
}

const char* const diffuse_f_doc = R"(A diffuse model's BRDF f(wi, wo) in 1/sr, without the cosine: the value of the
fitter's DiffuseModel::f (the fit's tables hold f cos theta_o). The light at theta_i, the viewer at theta_o (degrees
in [0, 90)), phi the azimuth of wo from the plane of wi (degrees); alpha the GGX roughness in (0, 1] (Disney's
perceptual roughness squared), albedo in [0, 1]; the five broadcast against each other (NumPy's rules), a Python float
when all are scalars. constants: None for the model's published ones, else a sequence of its constants in the order
smithlab.diffuse_models() lists them (ValueError naming the model and the count otherwise).)";

// ---- a fit's constants ------------------------------------------------------------------------------------------

// The columns of constants.csv that read_fit uses (others, the NDF parameters after ndf, are in the ndf label).
struct ConstantsColumns {
    std::size_t model, ndf, parameter, value, stderr_, width;
};

// "PATH:LINE: " for messages.
std::string at(const fs::path& file, std::size_t line) { return file.string() + ":" + std::to_string(line) + ": "; }

ConstantsColumns columns_of(const CsvRecord& header, const fs::path& file) {
    auto find = [&](std::string_view name) {
        for (std::size_t i = 0; i < header.fields.size(); ++i)
            if (header.fields[i] == name) return i;
        throw input_error(at(file, header.line) + "no column '" + std::string(name) +
                          "' (a fit's constants.csv starts model,ndf,...,parameter,value,stderr)");
    };
    return {find("model"), find("ndf"), find("parameter"), find("value"), find("stderr"), header.fields.size()};
}

// A row's model: the fitter's model named "<model>-fitted" in the file, checked against the known models and their
// constants.
std::string model_of(const std::string& text, const std::string& constant, const std::string& where) {
    constexpr std::string_view suffix = "-fitted";
    if (text.size() <= suffix.size() || text.compare(text.size() - suffix.size(), suffix.size(), suffix) != 0)
        throw input_error(where + "model '" + text + "' is not a fitted model's name (<model>-fitted)");
    const std::string name = text.substr(0, text.size() - suffix.size());
    try {
        const fit::DiffuseModel& m = fit::find_diffuse_model(name);
        for (std::string_view p : m.parameters)
            if (p == constant) return name;
        throw input_error("model '" + name + "' has no constant '" + constant +
                          "' (its constants: " + constant_names(m) + ")");
    } catch (const input_error& e) {
        throw input_error(where + e.what());
    }
}

double number_of(const std::string& text, const std::string& what) {
    const double v = parse_double(text, what);
    require(std::isfinite(v), what, "finite", v);
    return v;
}

// model -> ndf label -> constant -> value (or its standard error)
using FitConstants = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;

FitConstants read_constants(const fs::path& directory, bool standard_errors) {
    const fs::path file = directory / "constants.csv";
    std::ifstream in(file, std::ios::binary);
    if (!fs::is_regular_file(file) || !in)
        throw input_error("read_fit: " + file.string() + ": no such file (a `smithlab fit` output directory holds it)");
    const std::vector<CsvRecord> records = read_csv(in);
    if (records.empty()) throw input_error("read_fit: " + file.string() + ": empty, not even a header");
    if (!records.front().error.empty()) throw input_error(at(file, records.front().line) + records.front().error);
    const ConstantsColumns c = columns_of(records.front(), file);
    FitConstants out;
    for (std::size_t r = 1; r < records.size(); ++r) {
        const CsvRecord& rec = records[r];
        const std::string where = at(file, rec.line);
        if (!rec.error.empty()) throw input_error(where + rec.error);
        if (rec.fields.size() != c.width)
            throw input_error(where + std::to_string(rec.fields.size()) + " fields where the header has " +
                              std::to_string(c.width));
        const std::string& constant = rec.fields[c.parameter];
        const std::string model = model_of(rec.fields[c.model], constant, where);
        const double value = number_of(rec.fields[c.value], where + "value");
        const double error = number_of(rec.fields[c.stderr_], where + "stderr");
        if (!out[model][rec.fields[c.ndf]].emplace(constant, standard_errors ? error : value).second)
            throw input_error(where + "a second row of " + rec.fields[c.model] + " on " + rec.fields[c.ndf] + ", " +
                              constant);
    }
    for (const auto& [model, by_ndf] : out)  // every constant of the model, for every NDF it was fitted on
        for (const auto& [ndf, constants] : by_ndf)
            for (std::string_view p : fit::find_diffuse_model(model).parameters)
                if (!constants.count(std::string(p)))
                    throw input_error("read_fit: " + file.string() + ": " + model + "-fitted on " + ndf +
                                      " has no row for its constant " + std::string(p));
    return out;
}

py::dict read_fit(const fs::path& directory, bool standard_errors) {
    py::dict out;
    for (const auto& [model, by_ndf] : read_constants(directory, standard_errors)) {
        py::dict ndfs;
        for (const auto& [ndf, constants] : by_ndf) {
            py::dict values;  // in the model's order of its constants (diffuse_f's), whatever the file's
            for (std::string_view p : fit::find_diffuse_model(model).parameters)
                values[py::str(std::string(p))] = constants.at(std::string(p));
            ndfs[py::str(ndf)] = values;
        }
        out[py::str(model)] = ndfs;
    }
    return out;
}

const char* const read_fit_doc = R"(The fitted constants of a `smithlab fit` output directory (its constants.csv), as
{model: {ndf: {constant: value}}}: model the fitter's model name (the file's '<model>-fitted' rows, so that
smithlab.diffuse_f(model, ..., constants=list(d[model][ndf].values())) is the fitted model), ndf the NDF family as the
file names it ('ggx', 'gtr(gamma=1.5)'), the constants in the model's order. stderr=True gives their standard errors
in the same shape. A missing file, or a malformed row, raises ValueError naming the file and the line.)";

// ---- compensation -----------------------------------------------------------------------------------------------

py::dict compensation(const AnyNdf& ndf, int cosines, const std::string& g2) {
    require(cosines >= 2 && cosines <= 4096, "cosines", "in [2, 4096] (as the fit's [compensation] cosines)", cosines);
    if (g2 != "height-correlated" && g2 != "separable")
        throw input_error("g2 must be 'height-correlated' or 'separable', got '" + g2 + "'");
    compensation::AlbedoOptions opts;
    opts.tolerance = compensation::table_tolerance;  // as the fit's tables
    opts.g2 = g2 == "separable" ? G2Form::uncorrelated : G2Form::height_correlated;
    std::vector<double> mus, E;
    double missing = 0.0, scale = 0.0;
    {
        const SignalPoll poll;
        py::gil_scoped_release free;
        const compensation::SingleScatteringAlbedo<AnyNdf> albedo(ndf, opts);
        scale = albedo.warp_scale();
        for (int j = 0; j < cosines; ++j) {
            poll();
            mus.push_back(compensation::unwarp_cosine(scale, static_cast<double>(j) / (cosines - 1)));
            E.push_back(albedo(mus.back()));
        }
        missing = albedo.missing();
    }
    py::dict out;
    out["cos_theta"] = py::array_t<double>(static_cast<py::ssize_t>(mus.size()), mus.data());
    out["E"] = py::array_t<double>(static_cast<py::ssize_t>(E.size()), E.data());
    out["E_avg"] = 1.0 - missing;
    out["one_minus_E_avg"] = missing;
    out["warp_scale"] = scale;
    return out;
}

const char* const compensation_doc = R"(One alpha's row of the energy-compensation table of the NDF (Kulla and Conty
2017): E, the directional albedo of single scattering off mirror facets (dimensionless), at the table's warped
cosines cos_theta = c x^2 / (1 + c - x^2), x = j / (cosines - 1) (0 grazing, 1 normal; compensation/albedo_grid.hpp), c the
NDF's warp scale (6 cos(theta) where its Lambda = 0.3), and 1 - E_avg = 2 integral of (1 - E(mu)) mu dmu by its own
quadrature; g2 'height-correlated' (E(0) = 1, the limit) or 'separable' (G1 G1). A dict: 'cos_theta' and 'E'
(float64 arrays of `cosines`), 'E_avg', 'one_minus_E_avg' and 'warp_scale' (floats). The same bits as the fit's
compensation.csv and compensation_avg.csv rows of that NDF and G2. By quadrature (compensation/compensation.hpp, relative
tolerance 1e-8); ~0.2 ms a cosine. Runs without the GIL.)";

}  // namespace

void bind_fit(py::module_& m) {
    m.def("diffuse_models", &models,
          "The diffuse models the fitter fits (as `smithlab fit --list-models`): dicts of name, description (the "
          "source), constants (the names of the free constants, empty for a fixed baseline), published (their "
          "published or starting values) and glsl (whether the fit exports it as GLSL: False for a model that has "
          "none).");
    m.def("diffuse_f", &diffuse_f, py::arg("model"), py::arg("theta_i"), py::arg("theta_o"), py::arg("phi"),
          py::arg("alpha"), py::arg("albedo"), py::arg("constants") = py::none(), diffuse_f_doc);
    m.def("read_fit", &read_fit, py::arg("directory"), py::kw_only(), py::arg("stderr") = false, read_fit_doc);
    m.def("compensation", &compensation, py::arg("ndf"), py::arg("cosines") = 48, py::arg("g2") = "height-correlated",
          compensation_doc);
}

}  // namespace smithlab::python
