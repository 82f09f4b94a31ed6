#include "fit/point_cache.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "output/sealed_file.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

std::string cache_key(const AnyNdf& ndf, const std::string& material, const std::string& set, std::int64_t walks,
                      std::uint64_t seed, std::uint64_t stream, std::size_t points, walk::EvalEstimator estimator) {
    std::ostringstream k;
    k << "smithlab " << SMITHLAB_VERSION << "|ndf=" << ndf.key() << "|material=" << material << "|set=" << set
      << "|walks=" << walks << "|seed=" << seed << "|stream=" << stream << "|points=" << points
      << "|eval=" << walk::name(estimator);  // the eval points' estimator
    return k.str();
}

std::optional<std::vector<fit::SplitMoments>> read_cache(const CacheFile& file) {
    const std::optional<std::string> body = output::read_sealed(file.path, "fit: cache " + file.path.string());
    if (!body) return std::nullopt;
    std::istringstream in{*body};
    std::vector<CsvRecord> rows;
    try {
        rows = read_csv(in);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (rows.size() != file.points.size() + 2 || rows[0].fields != std::vector<std::string>{"key", file.key})
        return std::nullopt;
    for (const CsvRecord& r : rows)
        if (!r.error.empty()) return std::nullopt;
    std::vector<fit::SplitMoments> out(file.points.size());
    for (std::size_t j = 0; j < file.points.size(); ++j) {
        const std::vector<std::string>& f = rows[j + 2].fields;
        const std::vector<std::string>& want = file.points[j];
        if (f.size() < want.size() || !std::equal(want.begin(), want.end(), f.begin())) return std::nullopt;
        if (!fit::read_moment_fields(f, want.size(), out[j]) || out[j].walks != file.walks) return std::nullopt;
    }
    return out;
}

void write_cache(const CacheFile& file, const std::vector<fit::SplitMoments>& moments) {
    std::ostringstream body;
    write_csv_record(body, {"key", file.key});
    std::vector<std::string> header = file.columns;
    for (std::string& c : fit::moment_columns()) header.push_back(std::move(c));
    write_csv_record(body, header);
    for (std::size_t j = 0; j < file.points.size(); ++j) {
        std::vector<std::string> f = file.points[j];
        for (std::string& x : fit::moment_fields(moments[j])) f.push_back(std::move(x));
        write_csv_record(body, f);
    }
    fs::create_directories(file.path.parent_path());
    output::write_sealed(file.path, body.str());
}

std::string cache_directory_name(const std::string& label) {
    std::string d = label;
    for (char& c : d)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-')) c = '_';
    return d;
}

}  // namespace smithlab::fit
