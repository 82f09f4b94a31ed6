// smithlab/quadrature.hpp -- one call, two backends, relative stopping rule.
//
// Boost.Math: tanh-sinh on [a, b] and exp-sinh on [a, inf) (double-exponential, bounded cost).
// GSL: QAG (21-point Gauss-Kronrod, globally adaptive) and QAGIU for [a, inf).
// Both stop on a *relative* error. An absolute rule silently returns three correct digits when the integral is
// 1e-78 (DESIGN.md, "Numerical facts").
#pragma once

#include <string>
#include <string_view>
#include <type_traits>

namespace smithlab {

enum class Backend { boost, gsl };

Backend parse_backend(std::string_view name);  // "boost" | "gsl", throws input_error otherwise
std::string_view to_string(Backend b);

struct QuadratureOptions {
    Backend backend = Backend::boost;
    double tolerance = 1e-12;  // relative
};

// A non-owning reference to a callable double(double): no allocation, one indirect call per node.
class FunctionRef {
public:
    template <class F>
        requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef>)
    FunctionRef(const F& f)  // NOLINT(google-explicit-constructor): implicit by design
        : obj_(&f), call_([](const void* o, double x) { return (*static_cast<const F*>(o))(x); }) {}
    double operator()(double x) const { return call_(obj_, x); }

private:
    const void* obj_;
    double (*call_)(const void*, double);
};

// integral_a^b f(x) dx, a < b finite, or b = +inf.
double integrate(FunctionRef f, double a, double b, const QuadratureOptions& opts = {});

}  // namespace smithlab
