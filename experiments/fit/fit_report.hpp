// The fit's report.md: per NDF family the errors of every model on the validation set, best first; the fits that look
// wrong (fit/fit_flags.hpp); the fitted constants; then the sections the run adds (trends, compensation, pictures).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_results.hpp"

namespace smithlab::fit {

// The report's opening: the scene's title and how its data were traced and weighed.
struct ReportHeading {
    std::string title, material;
    std::vector<double> albedos;
    double floor;
};

void write_report(const std::filesystem::path& dir, const ReportHeading& heading, const Results& results,
                  const std::vector<ErrorRow>& errors, const std::string& flags, const std::string& sections);

}  // namespace smithlab::fit
