/// @file
/// smithlab/csv.hpp -- RFC 4180 CSV: quoted fields (with commas, doubled quotes and line breaks), CRLF or LF.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace smithlab {

/// One record of a CSV file (RFC 4180), as read_csv returns it.
struct CsvRecord {
    std::size_t line = 0;  ///< physical line where the record starts, 1-based
    /// The record's fields, unquoted.
    std::vector<std::string> fields;
    std::string error;  ///< non-empty when the record is malformed (bad quoting); fields are then unusable
};

/// Every record of the stream, blank lines skipped. Malformed records are returned with `error` set, so that a
/// caller can report each bad row by its line and keep going.
std::vector<CsvRecord> read_csv(std::istream& in);

/// printf's text of the arguments by `format` (std::vsnprintf), whatever its length; the compiler checks the format
/// against the arguments.
[[gnu::format(printf, 1, 2)]] std::string format_printf(const char* format, ...);
/// A number with 17 significant digits ("%.17g"): every double round-trips.
std::string format_g17(double v);
/// The shortest text that reads back as v (std::to_chars): 0.1 as "0.1", where "%.17g" gives 0.10000000000000001.
std::string format_shortest(double v);

/// One field, quoted only when it must be (comma, quote, CR or LF inside).
std::string csv_field(std::string_view s);
/// One record: the fields as csv_field writes them, joined by commas, then LF.
void write_csv_record(std::ostream& out, const std::vector<std::string>& fields);

}  // namespace smithlab
