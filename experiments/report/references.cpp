#include "report/references.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>

#include "output/output_file.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

const char* name_of(LambdaRoute r) {
    return r == LambdaRoute::closed ? "closed" : r == LambdaRoute::q1d_boost ? "q1d-boost-1e-13" : "q2d-boost-1e-12";
}

LambdaRoute route_for(const LambdaVariant& v, const AnyNdf& ndf) {
    const LambdaRoute own = route_on(v, ndf);
    for (LambdaRoute r : reference_routes)
        if (r != own && (r != LambdaRoute::closed || ndf.has_closed_Lambda())) return r;
    return LambdaRoute::q2d_boost;  // not reached: at most one reference route is the variant's own
}

double compute_reference(const AnyNdf& ndf, double mu, LambdaRoute r) {
    switch (r) {
        case LambdaRoute::closed:
            return ndf.Lambda(mu);
        case LambdaRoute::q1d_boost:
            return Lambda_1d(ndf, mu, {Backend::boost, 1e-13});
        case LambdaRoute::q2d_boost:
            return Lambda_2d(ndf, mu, {Backend::boost, 1e-12});
        default:
            return NAN;  // not a reference route
    }
}

void require_row_domain(const LambdaVariant& v, const AnyNdf& ndf, double mu) {
    if (is_quadrature(route_on(v, ndf)) || is_quadrature(route_for(v, ndf))) require_quadrature_domain(ndf, mu);
}

namespace {

// A record's check: FNV-1a (64 bit) of its fields, in hex. A record cut short, edited or half-written does not
// match it and is computed again.
std::string check_of(const std::string& spec, const std::string& mu, const std::string& route,
                     const std::string& lambda) {
    std::uint64_t h = 14695981039346656037ull;
    for (const std::string* f : {&spec, &mu, &route, &lambda}) {
        for (unsigned char c : *f) h = (h ^ c) * 1099511628211ull;
        h = (h ^ 0x1fu) * 1099511628211ull;  // a field separator no field holds
    }
    return format_printf("%016llx", static_cast<unsigned long long>(h));
}

}  // namespace

ReferenceCache::ReferenceCache(fs::path file) : file_(std::move(file)) {
    std::ifstream in(file_);
    if (!in) return;
    const auto records = read_csv(in);
    for (std::size_t i = 1; i < records.size(); ++i) {
        const std::vector<std::string>& f = records[i].fields;
        char* end = nullptr;
        const double v = f.size() == 5 ? std::strtod(f[3].c_str(), &end) : NAN;
        if (!records[i].error.empty() || f.size() != 5 || end != f[3].c_str() + f[3].size() || !std::isfinite(v) ||
            check_of(f[0], f[1], f[2], f[3]) != f[4]) {
            ++discarded_;
            continue;
        }
        values_[f[0] + "|" + f[1] + "|" + f[2]] = v;
    }
    loaded_ = values_.size();
}

double ReferenceCache::get(const AnyNdf& ndf, double mu, LambdaRoute r) {
    const std::string key = ndf.spec() + "|" + format_g17(mu) + "|" + name_of(r);
    if (auto it = values_.find(key); it != values_.end()) return it->second;
    ++computed_;
    return values_[key] = compute_reference(ndf, mu, r);
}

void ReferenceCache::save() const {
    std::error_code ec;
    fs::create_directories(file_.parent_path(), ec);
    if (ec)
        throw input_error("cannot create the reference cache's directory '" + file_.parent_path().string() +
                          "': " + ec.message());
    output::write_output(output::resolve_output(file_.string()), [&](std::ostream& out) {
        write_csv_record(out, {"spec", "mu", "route", "lambda", "check"});
        for (const auto& [key, v] : values_) {
            const auto a = key.find('|'), b = key.find('|', a + 1);
            const std::string spec = key.substr(0, a), mu = key.substr(a + 1, b - a - 1), route = key.substr(b + 1);
            const std::string lambda = format_g17(v);
            write_csv_record(out, {spec, mu, route, lambda, check_of(spec, mu, route, lambda)});
        }
    });
}

}  // namespace smithlab::report
