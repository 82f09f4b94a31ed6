// A text file sealed by a last line `checksum,HEX` (smithlab/util/checksum.hpp), written and read whole: the files a
// run keeps so that a later one reuses them, the fitter's cache of traced points (fit/point_cache.hpp) and the trace's
// cell files (trace/cell_file.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace smithlab::output {

// Writes `body` and its seal atomically (output_file.hpp: a temporary renamed into place): a killed run leaves the
// file whole or absent.
void write_sealed(const std::filesystem::path& path, const std::string& body);

// The file's text without its seal. nullopt when the file cannot be opened (absent: nothing is said), or when its
// seal does not hold (a file cut short, edited, with bits flipped or written without a seal): then the line
// "NAME: checksum mismatch, traced again" goes to stderr, `name` saying which file of which command
// ("trace: cell 3", "fit: cache PATH").
std::optional<std::string> read_sealed(const std::filesystem::path& path, const std::string& name);

}  // namespace smithlab::output
