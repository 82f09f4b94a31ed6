#include "fit/fit_flags.hpp"

#include <cstdio>
#include <sstream>

#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace {

std::string g5(double v) { return format_printf("%.5g", v); }

// "[0, 1.5708]", "[0, inf)", "(-inf, inf)".
std::string range_text(const fit::ParameterRange& r) {
    return format_printf("%s%.5g, %.5g%s", r.lo == -INFINITY ? "(" : "[", r.lo, r.hi, r.hi == INFINITY ? ")" : "]");
}

void flag_ranges(std::vector<Flag>& out, const Measured& m, const std::string& ndf) {
    for (std::size_t i = 0; i < m.params.size(); ++i)
        if (const fit::ParameterRange* r = fit::outside_range(*m.model, i, m.params[i])) {
            const bool at = m.params[i] == r->lo || m.params[i] == r->hi;
            out.push_back({m.name, ndf,
                           std::string(m.model->parameters[i]) + " = " + g5(m.params[i]) +
                               (at ? " is at a bound of" : " is beyond") + " its range " + range_text(*r) + ": " +
                               std::string(r->why)});
        }
}

void flag_worse(std::vector<Flag>& out, const ErrorRow& fitted, const ErrorRow& start) {
    const struct {
        const char* name;
        double fitted, start;
    } errors[] = {{"RMS relative error", fitted.rms_rel, start.rms_rel},
                  {"RMS error of the directional albedo", fitted.albedo_rms, start.albedo_rms},
                  {"chi^2 / value", fitted.chi2_dof, start.chi2_dof}};
    for (const auto& e : errors)
        if (e.fitted > e.start)
            out.push_back({fitted.model, fitted.ndf,
                           std::string("its ") + e.name + " on the validation set, " + g5(e.fitted) +
                               ", is worse than at its starting constants (" + g5(e.start) + ")"});
}

}  // namespace

std::vector<Flag> flag_fit(const Measured& fitted, const ErrorRow& errors, const ErrorRow& at_start) {
    std::vector<Flag> out;
    flag_ranges(out, fitted, errors.ndf);
    flag_worse(out, errors, at_start);
    return out;
}

std::string flags_markdown(const std::vector<Flag>& flags) {
    std::ostringstream md;
    md << "\n## Fits that look wrong\n\n"
       << "A fit is flagged where a fitted constant ends at or beyond the range in which its model means what its "
          "source says (each flag gives the range and why), or where the fitted model measures worse on "
          "the validation set than at its starting constants (RMS relative error, RMS error of the directional "
          "albedo, chi^2 / value): the model cannot follow the data there, and its fitted constants are not to be "
          "read as physical.\n\n";
    if (flags.empty()) md << "None.\n";
    for (const Flag& f : flags) md << "- **" << f.model << "** on " << f.ndf << ": " << f.what << "\n";
    return md.str();
}

void print_flags(const std::vector<Flag>& flags) {
    for (const Flag& f : flags)
        std::fprintf(stderr, "fit: warning: %s on %s: %s\n", f.model.c_str(), f.ndf.c_str(), f.what.c_str());
}

}  // namespace smithlab::fit
