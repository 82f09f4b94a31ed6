// The fitter's cache of traced points (OUT/cache/NDF/...csv): one file per group of points traced together, line 1
// `key,KEY`, line 2 the header (the points' own columns, then fit::moment_columns), then a row per point: its own
// fields (its directions, 17 digits) and its moments (read back bit for bit), and last `checksum,HEX`, the CRC-64 of
// every byte above it, the key line included (smithlab/util/checksum.hpp). A file is reused only when its checksum
// holds, its key is the one asked for (all that defines the trace: version, NDF, material, set, walks, seed, stream,
// points, the eval estimator), every point's fields are the ones asked for and its moments are finite numbers: a
// changed scene or NDF never reuses stale data (and says nothing), and a file cut short, with a value edited, bits
// flipped or rows swapped is traced again with a line on stderr ("fit: cache PATH: checksum mismatch, traced again").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fit/dataset.hpp"

namespace smithlab::fit {

struct CacheFile {
    std::filesystem::path path;
    std::string key;
    std::vector<std::string> columns;              // the points' own columns, e.g. theta_i, theta_o, phi
    std::vector<std::vector<std::string>> points;  // per point: its fields under those columns
    std::int64_t walks = 0;                        // per point
};

// "smithlab VERSION|ndf=NDF KEY|material=...|set=SET|walks=N|seed=S|stream=FIRST STREAM|points=N|eval=ESTIMATOR"
// (the eval points' estimator: a cache traced by another is traced again).
std::string cache_key(const AnyNdf& ndf, const std::string& material, const std::string& set, std::int64_t walks,
                      std::uint64_t seed, std::uint64_t stream, std::size_t points, walk::EvalEstimator estimator);

// The moments of the file's points, when the checksum holds and the file is this one (key, fields, walks); nullopt
// otherwise (a present file whose checksum fails is named on stderr).
std::optional<std::vector<fit::SplitMoments>> read_cache(const CacheFile& file);

// Writes the file whole (output/output_file.hpp: a temporary renamed into place), creating its directory.
void write_cache(const CacheFile& file, const std::vector<fit::SplitMoments>& moments);

// An NDF label as a directory name: letters, digits, '.', '=' and '-' kept, anything else '_'.
std::string cache_directory_name(const std::string& label);

}  // namespace smithlab::fit
