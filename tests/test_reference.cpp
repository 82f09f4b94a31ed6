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
