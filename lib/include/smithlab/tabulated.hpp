/// @file
/// smithlab/tabulated.hpp -- a measured isotropic NDF: D(theta_m) given as a table (CSV), interpolated into an NDF type
/// (ndf.hpp: D and its slope form P22).
///
/// The file. A header line names the columns: the angle, as `theta_deg` (theta_m in degrees, in [0, 90)) or
/// `cos_theta` (in (0, 1]), and `D` (per steradian of m, normalized so that the integral of D(m) cos(theta_m) over the
/// hemisphere is 1, Walter et al. 2007 eq. 4); other columns are ignored. Then one row per angle, theta_m strictly
/// increasing (cos_theta strictly decreasing), D finite and >= 0. RFC 4180 as csv.hpp reads it; a line whose first
/// character is '#' (outside a quoted field) is a comment, and a leading UTF-8 byte order mark is skipped. Every
/// refusal is an input_error "FILE:LINE: ..." naming the value (the area's names the rows' lines), and comes before any
/// TabulatedNdf exists.
///
/// The interpolation, chosen by measurement (tests/test_tabulated.cpp prints the table; see "Measured" below):
///   nodes      y_i = ln D_i against theta_i in radians: D is what a measurement gives as a function of theta, and ln D
///              of every family here is smooth in theta up to the horizon. In r = tan theta (or r^2) the last intervals
///              stretch over decades, and a cubic there missed GGX's Lambda by 8-12 % near mu = 15 on 60 rows to 89
///              degrees, where ln D in theta missed it by 1e-4 (alpha 0.1) and 4e-6 (alpha 0.5). ln P22 in ln r came
///              close (6e-5, 8e-5; on Beckmann 0.6-2.5x theta's error) and has no node at the pole.
///   segments   cubic Hermite in theta, slopes by Steffen's rule (M. Steffen 1990, "A simple method for monotonic
///              interpolation in one dimension", A&A 239, 443, eq. 11 inside, eq. 26-27 at the ends): each piece is
///              monotone and stays between its two values, so D never leaves the range of its neighbours (no
///              overshoot to a negative or huge D from noise). Fritsch-Carlson's harmonic mean (PCHIP) did as well
///              on GGX to 85 degrees, 1.3-6x worse to 89, up to 18x worse on Beckmann. A node with D = 0 cannot be
///              logged: a piece with a zero end is linear in D itself.
///   the pole   below the first angle theta_0 > 0, ln D = y_0 + b (theta^2 - theta_0^2), b = y'_0 / (2 theta_0), y'_0
///              the spline's end slope: even in theta, as D is (P22 is even in the slope), value and slope continuous
///              at theta_0. With a row at theta = 0, the slope there is 0 for the same reason.
///   the tail   past the last angle theta_n, D linear in cos^2 theta_m:
///                  D = D_0 + D_1 cos^2 theta_m,   D_0 + D_1 cos^2 theta_n = D_n,
///              D_1 the least-squares slope of D against cos^2 over the last four rows, D_0 clamped to
///              [0, max D of those rows] (then D_1 from the pin). The first term of D's expansion at the horizon for
///              every NDF smooth in cos^2 there (GGX, GTR: D = f(cos^2)); in slopes P22 = (D_0 + D_1 c^2) c^4,
///              c^2 = 1 / (1 + r^2): P22 ~ D_0 r^-4 (or D_1 r^-6 when D_0 = 0), so Lambda and the normalization stay
///              finite, D is finite at the horizon, and P22(inf) = 0. A power law P22 ~ r^-k fitted to the last rows
///              (k clamped >= 4) missed GGX(0.5)'s Lambda at mu = 100 by 3.8e-3 for data to 85 degrees; this law by
///              1.5e-4 (the cos^4 term it leaves out).
/// D and P22 are finite and >= 0 everywhere (0 for cos <= 0), NaN in, NaN out. No member allocates, locks or throws:
/// any number of threads may call them at once.
///
/// Measured (tests/test_tabulated.cpp, GGX, Beckmann, GTR at gamma 1.5 sampled at jittered angles): the worst relative
/// error of Lambda over mu in [0.01, 100] is 3e-6 to 1e-4 on 60 rows to 89 degrees, 6e-7 to 1.3e-6 on 200. On rows to
/// 85 degrees, GGX and GTR are off by 1.4e-4 to 5.2e-4 whatever the count, at mu ~ 100: the tail law's (Beckmann's
/// tail is 0 there: 5e-7 to 3e-5).
///
/// Quadrature. The interpolant is C1: its second derivative jumps at every row. GSL's adaptive Gauss-Kronrod resolves
/// that (run_checks with Backend::gsl: every residual below 5e-9); Boost's tanh-sinh, made for analytic integrands,
/// gets the checks' visible projected area only to ~1e-7 and its nested 2D route takes minutes. Lambda by the default
/// route (the fixed rule, lambda_fixed.hpp) agrees with GSL's to ~3e-10.
///
/// The normalization: the projected area A = 2 pi integral_0^{pi/2} D sin cos dtheta = pi integral_0^inf P22 d(r^2)
/// (Walter 2007 eq. 4 and 42) of the interpolant itself, by 8-point Gauss-Legendre on each piece (the pole's too) and
/// the tail in closed form, pi D_0 c_n^2 + pi D_1 c_n^4 / 2. A table with |A - 1| > tabulated_area_tolerance is
/// refused, unless TabulatedOptions::normalize; within it, or with normalize, D is divided by A (normalization_factor()
/// = 1 / A, reported by note()): the Smith model holds only for a normalized D.
///
/// The identity: content_hash() is FNV-1a 64 (Fowler, Noll, Vo) of the bytes of the CSV text as read, comments and
/// line ends included, the source name not: a cache keyed on it follows the contents, not the path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "smithlab/quadrature.hpp"

namespace smithlab {

/// |A - 1| allowed for a table read without `normalize`. 1e-2, from what normalized measurements carry: 1 % noise per
/// row moves A of the two-lobe table (experiments/ndfs/) by a standard deviation of 1.5e-3 on 120 rows (worst of 200
/// draws 3.8e-3, tests/test_tabulated.cpp), and a producer who normalized with the trapezoid rule in theta on 120
/// rows is off by 1.4e-3 for that mixture, 4.4e-3 for a lone GGX lobe of alpha 0.08 (on 60 rows, 5e-3 and 1.7e-2:
/// read those with normalize). A D off by more (a missing factor pi or cos theta_m, other units) is refused.
inline constexpr double tabulated_area_tolerance = 1e-2;
/// The fewest rows the interpolation takes: Steffen's end slope is the three-point parabola's.
inline constexpr std::size_t tabulated_min_points = 3;
/// The most bytes a table file may hold: 64 MiB, a million rows of 17-digit pairs and more, far beyond a measured
/// D(theta); /dev/zero, an endless pipe or a mistaken file is refused without being held.
inline constexpr std::size_t tabulated_max_bytes = std::size_t{64} << 20;

/// How a table is read.
struct TabulatedOptions {
    bool normalize = false;  ///< divide D by its projected area A instead of refusing |A - 1| >
                             ///< tabulated_area_tolerance
};

namespace detail {
struct TabulatedTable;
}

/// A measured isotropic NDF: D(theta_m) from a table (the file comment), an NDF in the sense of ndf.hpp.
class TabulatedNdf {
public:
    /// D(cos theta_m): 0 for cos <= 0; cos > 1 (rounding) is read as 1.
    double D(double cos_theta_m) const;
    /// P22(r^2) = D cos^4 at r^2 = tan^2 theta_m (Walter 2007 eq. 42); 0 at r^2 = inf.
    double slope_density(double r2) const;

    std::size_t points() const;  ///< rows in the table
    /// @{
    double theta_min_deg() const;  ///< the table's first and last angle, in degrees
    double theta_max_deg() const;
    /// @}
    double horizon_D() const;             ///< D_0: D at theta_m = 90 degrees, from the tail law
    double area_as_read() const;          ///< A before any rescaling
    double normalization_factor() const;  ///< 1 / A: what D was multiplied by
    std::uint64_t content_hash() const;   ///< FNV-1a 64 of the CSV bytes as read
    std::string content_id() const;       ///< "fnv1a64:" and the hash as 16 hex digits
    const std::string& source() const;    ///< the name the table was read under (a path, or the caller's)

    /// The table's distribution with its slopes stretched by s: P22_s(r^2) = P22(r^2 / s^2) / s^2 (a distribution of
    /// slopes scaled by s; still normalized), s in [1e-4, 1e4] (input_error otherwise). Its core slope scale
    /// (ndf.hpp, core_slope_scale) is s times the table's: what a roughness alpha sets (the registry's "tabulated").
    TabulatedNdf scaled(double s) const;
    /// The slope scale s it was stretched by (scaled()), 1 for the table as read.
    double scale() const { return scale_; }
    /// "" unless D was rescaled by more than 1e-9 (|A - 1| >= 1e-9): then the factor and the area it came from.
    std::string note() const;
    /// The quadrature its integrals need (lambda_table.hpp: the walk's and the samplers' Lambda table): GSL's adaptive
    /// Gauss-Kronrod, which resolves the interpolant's kinks (tanh-sinh spent minutes on one table of the example).
    static std::optional<Backend> quadrature_backend() { return Backend::gsl; }

private:
    explicit TabulatedNdf(std::shared_ptr<const detail::TabulatedTable> table) : t_(std::move(table)) {}
    friend TabulatedNdf tabulated_ndf_from_csv(const std::string&, const std::string&, const TabulatedOptions&);
    double table_P22(double r2) const;
    std::shared_ptr<const detail::TabulatedTable> t_;
    double scale_ = 1.0;
};

/// The NDF of CSV `text`; `source` names it in messages ("SOURCE:LINE: ...") and in source(). input_error on any
/// refusal above.
TabulatedNdf tabulated_ndf_from_csv(const std::string& text, const std::string& source,
                                    const TabulatedOptions& opts = {});
/// The same from a file, read as bytes; the path as given is the source. input_error when it cannot be read, is not a
/// regular file (a FIFO is refused before it is opened, not waited on; so are devices) or holds more than
/// tabulated_max_bytes.
TabulatedNdf read_tabulated_ndf(const std::filesystem::path& path, const TabulatedOptions& opts = {});

/// FNV-1a 64 of bytes (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
std::uint64_t fnv1a64(std::string_view bytes);

}  // namespace smithlab
