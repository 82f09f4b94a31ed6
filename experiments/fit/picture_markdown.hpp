// The pictures' section of report.md (fit/fit_pictures.hpp): what each picture shows, the checks, and the measured
// fraction of light single scattering misses against Hammon 2017's "up to half".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fit/fit_results.hpp"
#include "fit/fit_scene.hpp"
#include "fit/picture_tables.hpp"

namespace smithlab::fit {

// A check's result: the largest relative difference of Lambertian facets from Lambert's law per NDF at the smallest
// sphere alpha.
struct LambertCheck {
    std::string ndf;
    double alpha, worst;
};

struct PictureReport {
    std::vector<std::string> labels;  // the NDFs, in order
    std::vector<Missing> missing;     // per NDF and sphere alpha, one per missing albedo
    std::vector<LambertCheck> checks;
    std::vector<std::string> swept;  // the constants_vs_* stems
    bool drawn = false;              // the plot script ran
    std::int64_t walks = 0;          // the walks the pictures hold
};

std::string pictures_markdown(const FitScene::Pictures& pictures, const PictureReport& report);

}  // namespace smithlab::fit
