// The 50-digit reference is only as good as its own check: its r-form quadrature must reproduce Dimov's printed
// closed forms (a different route entirely) and the Beckmann closed form to far more digits than any test asks.
#include <catch2/catch.hpp>

#include "reference.hpp"

TEST_CASE("50-digit r-form quadrature reproduces Dimov's printed closed forms", "[reference]") {
    for (int gamma = 0; gamma <= 4; ++gamma)
        for (double alpha : {1e-4, 0.3, 0.999999})
            for (double mu : {1e-4, 0.7, 1e4}) {
                if (gamma == 1 && alpha == 1.0) continue;
                const ref::real q = ref::Lambda(ref::gtr(alpha, gamma), mu);
                const ref::real c = ref::Lambda_dimov(gamma, alpha, mu);
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                CHECK(static_cast<double>(abs((q - c) / c)) < 1e-20);
            }
}

TEST_CASE("50-digit reference reproduces the Beckmann and GGX closed forms", "[reference]") {
    for (double alpha : {1e-3, 0.5})
        for (double mu : {1e-3, 0.4, 30.0}) {
            INFO("alpha=" << alpha << " mu=" << mu);
            const ref::real b = ref::Lambda(ref::beckmann(alpha), mu), bc = ref::Lambda_beckmann(alpha, mu);
            CHECK(static_cast<double>(abs((b - bc) / bc)) < 1e-20);
            const ref::real g = ref::Lambda(ref::ggx(alpha), mu), gc = ref::Lambda_dimov(2, alpha, mu);
            CHECK(static_cast<double>(abs((g - gc) / gc)) < 1e-20);
        }
}

TEST_CASE("50-digit uncut r-form reproduces Dimov's forms, and the STD paper's eq. 13 as printed", "[reference]") {
    // Lambda_uncut (in u = r / mu, no cut) against the printed forms: GGX and GTR gamma = 3 (r^-4 tails), and
    // the Student-t's eq. 13-15 (Ribardiere et al. 2017) evaluated literally at 100 digits, heavy tails included.
    for (double alpha : {1e-4, 0.3})
        for (double mu : {1e-4, 0.7, 1e4}) {
            INFO("alpha=" << alpha << " mu=" << mu);
            for (int gamma : {2, 3}) {
                const ref::real q = ref::Lambda_uncut(ref::gtr(alpha, gamma), mu),
                                c = ref::Lambda_dimov(gamma, alpha, mu);
                CHECK(static_cast<double>(abs((q - c) / c)) < 1e-20);
            }
        }
    for (double gamma : {1.6, 2.0, 2.5, 7.0, 40.0})
        for (double alpha : {1e-3, 0.5})
            for (double z : {1e-3, 0.7, 3.0, 30.0}) {
                const ref::real printed = ref::Lambda_student_printed(alpha, gamma, z * alpha);
                if (printed < ref::real("1e-40")) continue;  // eq. 13 cancels to 1/2: 100 digits leave 60 down to here
                const ref::real q = ref::Lambda_uncut(ref::student_t(alpha, gamma), z * alpha);
                INFO("gamma=" << gamma << " alpha=" << alpha << " z=" << z << ": " << static_cast<double>(q));
                CHECK(static_cast<double>(abs((q - printed) / printed)) < 1e-20);
            }
    // gamma = 2 is GGX as printed
    for (double mu : {1e-3, 0.4, 30.0}) {
        const ref::real s = ref::Lambda_uncut(ref::student_t(0.2, 2.0), mu), g = ref::Lambda_dimov(2, 0.2, mu);
        CHECK(static_cast<double>(abs((s - g) / g)) < 1e-20);
    }
}
