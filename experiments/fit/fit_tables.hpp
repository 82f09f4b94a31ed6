// The fit's tables: constants.csv and constants.json (the fitted constants and their standard errors), errors.csv
// (every model on the validation set), training.csv and validation.csv (the traced values beside every model's).
// Each CSV has one column per NDF parameter after its ndf column (fit/label_columns.hpp).
#pragma once

#include <filesystem>
#include <vector>

#include "fit/fit_results.hpp"
#include "fit/label_columns.hpp"

namespace smithlab::fit {

void write_constants(const std::filesystem::path& dir, const Results& results, const LabelColumns& columns);

void write_errors(const std::filesystem::path& dir, const std::vector<ErrorRow>& rows, const LabelColumns& columns);

// One row per point of the set and albedo: the traced value and its standard error, then each model's value.
enum class ValueSet { training, validation };
void write_values(const std::filesystem::path& file, const Results& results, ValueSet set,
                  const std::vector<double>& albedos, const LabelColumns& columns);

}  // namespace smithlab::fit
