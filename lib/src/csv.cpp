#include "smithlab/csv.hpp"

#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <istream>
#include <iterator>
#include <ostream>

namespace smithlab {

std::vector<CsvRecord> read_csv(std::istream& in) {
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<CsvRecord> records;
    std::size_t i = 0, line = 1;
    const std::size_t n = text.size();
    auto at_eol = [&](std::size_t k) {
        return k >= n || text[k] == '\n' || (text[k] == '\r' && (k + 1 >= n || text[k + 1] == '\n'));
    };
    auto skip_eol = [&] {
        if (i < n && text[i] == '\r') ++i;
        if (i < n && text[i] == '\n') ++i;
        ++line;
    };
    while (i < n) {
        if (at_eol(i)) {  // blank line
            skip_eol();
            continue;
        }
        CsvRecord rec;
        rec.line = line;
        std::string field;
        bool done = false;
        while (!done) {
            field.clear();
            if (i < n && text[i] == '"') {  // quoted field
                ++i;
                bool closed = false;
                while (i < n) {
                    if (text[i] == '"') {
                        if (i + 1 < n && text[i + 1] == '"') {
                            field += '"';
                            i += 2;
                            continue;
                        }
                        ++i;
                        closed = true;
                        break;
                    }
                    if (text[i] == '\n') ++line;
                    field += text[i++];
                }
                if (!closed) {
                    rec.error = "unterminated quoted field";
                    records.push_back(std::move(rec));
                    return records;
                }
                if (!(at_eol(i) || text[i] == ',')) rec.error = "characters after a closing quote";
            } else {
                while (!(at_eol(i) || text[i] == ',')) {
                    if (text[i] == '"') rec.error = "a quote inside an unquoted field";
                    field += text[i++];
                }
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
        records.push_back(std::move(rec));
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
