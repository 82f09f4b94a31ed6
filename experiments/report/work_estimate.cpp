#include "report/work_estimate.hpp"

#include <cmath>

#include "report/scene.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

// Above x, with two significant digits: a limit that lets a scene of work x through.
double rounded_up(double x) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::ceil(x / unit) * unit;
}

std::string short_number(double x) { return format_printf("%.3g", x); }

}  // namespace

void Work::add(const std::string& name, double count, bool shown_when_zero) {
    for (Part& p : parts)
        if (p.name == name) {
            p.count += count;
            p.shown_when_zero = p.shown_when_zero || shown_when_zero;
            return;
        }
    parts.push_back({name, count, shown_when_zero});
}

double Work::of(const std::string& name) const {
    for (const Part& p : parts)
        if (p.name == name) return p.count;
    return 0.0;
}

double Work::total() const {
    double sum = 0.0;
    for (const Part& p : parts) sum += p.count;
    return sum;
}

Work estimate_work(const Scene& scene, const VariantRegistry& variants) {
    Work w;
    for (const auto& section : scene.sections) section->add_work(w, scene.settings, variants);
    return w;
}

std::string describe(const Work& work) {
    std::string parts;
    for (const Work::Part& p : work.parts)
        if (p.count > 0.0 || p.shown_when_zero)
            parts += (parts.empty() ? "" : ", ") + p.name + " " + short_number(p.count);
    return short_number(work.total()) + " evaluations (" + parts + ")";
}

void check_work(const Work& work, double max_work, const std::string& source) {
    if (work.total() <= max_work) return;
    throw input_error(source + ": the scene's work is estimated at " + describe(work) + ", above the limit of " +
                      short_number(max_work) +
                      " evaluations; nothing was computed. Make the grid smaller, select fewer " +
                      "variants, samples or walks, or raise the limit: smithlab report --max-work " +
                      short_number(rounded_up(work.total())));
}

}  // namespace smithlab::report
