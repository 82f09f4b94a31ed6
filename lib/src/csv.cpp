#include "smithlab/csv.hpp"

#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <istream>
#include <iterator>
#include <ostream>

namespace smithlab {

namespace {

// A position in the text of a CSV stream and the physical line there.
struct CsvCursor {
    const std::string& text;
    std::size_t i = 0, line = 1;

    bool at_eol(std::size_t k) const {
        const std::size_t n = text.size();
        return k >= n || text[k] == '\n' || (text[k] == '\r' && (k + 1 >= n || text[k + 1] == '\n'));
    }
    void skip_eol() {
        if (i < text.size() && text[i] == '\r') ++i;
        if (i < text.size() && text[i] == '\n') ++i;
        ++line;
    }

    // The quoted field whose opening quote is at i, a doubled quote read as one; false when the text ends inside it.
    bool quoted_field(std::string& field) {
        const std::size_t n = text.size();
        ++i;
        while (i < n) {
            if (text[i] == '"') {
                if (i + 1 < n && text[i + 1] == '"') {
                    field += '"';
                    i += 2;
                    continue;
                }
                ++i;
                return true;
            }
            if (text[i] == '\n') ++line;
            field += text[i++];
        }
        return false;
    }

    // The unquoted field from i to the next comma or line end; a quote inside it sets error.
    void unquoted_field(std::string& field, std::string& error) {
        while (!(at_eol(i) || text[i] == ',')) {
            if (text[i] == '"') error = "a quote inside an unquoted field";
            field += text[i++];
        }
    }

    // The record starting at i, through its line end. A malformed record gets its error and ends at the end of the
    // physical line; false when the text ends inside a quoted field (nothing can follow).
    bool record(CsvRecord& rec) {
        rec.line = line;
        std::string field;
        bool done = false;
        while (!done) {
            field.clear();
            if (i < text.size() && text[i] == '"') {
                if (!quoted_field(field)) {
                    rec.error = "unterminated quoted field";
                    return false;
                }
                if (!(at_eol(i) || text[i] == ',')) rec.error = "characters after a closing quote";
            } else {
                unquoted_field(field, rec.error);
            }
            if (!rec.error.empty()) {  // resynchronize at the end of the physical line
                while (!at_eol(i)) ++i;
                done = true;
            } else if (at_eol(i)) {
                done = true;
            } else {
                ++i;  // the comma
            }
            rec.fields.push_back(field);
        }
        skip_eol();
        return true;
    }
};

}  // namespace

std::vector<CsvRecord> read_csv(std::istream& in) {
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<CsvRecord> records;
    CsvCursor at{text};
    while (at.i < text.size()) {
        if (at.at_eol(at.i)) {  // blank line
            at.skip_eol();
            continue;
        }
        CsvRecord rec;
        const bool more = at.record(rec);
        records.push_back(std::move(rec));
        if (!more) break;
    }
    return records;
}

std::string format_printf(const char* format, ...) {
    std::va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string text(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
    if (n > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
    va_end(again);
    return text;
}

std::string format_g17(double v) { return format_printf("%.17g", v); }

std::string format_shortest(double v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    return std::string(text, end);
}

std::string csv_field(std::string_view s) {
    if (s.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(s);
    std::string out = "\"";
    for (char c : s) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + '"';
}

void write_csv_record(std::ostream& out, const std::vector<std::string>& fields) {
    for (std::size_t k = 0; k < fields.size(); ++k) out << (k ? "," : "") << csv_field(fields[k]);
    out << '\n';
}

}  // namespace smithlab
