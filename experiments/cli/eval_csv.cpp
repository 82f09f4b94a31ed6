// smithlab eval --input: Lambda and G1 for every row of a CSV file with columns ndf and mu.
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "cli/eval_tables.hpp"
#include "output/ndf_columns.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

namespace {

// The records of the input file ('-': stdin), and the name its messages give it.
struct Input {
    std::string source;
    std::vector<CsvRecord> records;
};

Input read_input(const std::string& path) {
    if (path == "-") return {"<stdin>", read_csv(std::cin)};
    output::require_readable_input(path, "input file");
    std::ifstream file(path, std::ios::binary);
    if (!file) throw input_error("cannot open input file '" + path + "'");
    return {path, read_csv(file)};
}

// The positions of the columns ndf and mu in the header; a header without them, with one twice, or with a column
// eval writes is an input_error naming the file.
struct Columns {
    std::size_t ndf, mu;
};

Columns find_columns(const Input& in) {
    if (in.records.empty()) throw input_error(in.source + ": empty file, expected a header with columns ndf and mu");
    const CsvRecord& head = in.records.front();
    const std::string at = in.source + ":" + std::to_string(head.line) + ": ";
    if (!head.error.empty()) throw input_error(at + "header: " + head.error);
    int ndf = -1, mu = -1;
    std::string names;
    for (std::size_t k = 0; k < head.fields.size(); ++k) {
        const std::string& h = head.fields[k];
        int* col = h == "ndf" ? &ndf : h == "mu" ? &mu : nullptr;
        if (col && *col >= 0) throw input_error(at + "header has two '" + h + "' columns");
        if (col) *col = static_cast<int>(k);
        if (h == "lambda" || h == "g1")
            throw input_error(in.source + ": header already has a '" + h + "' column, which eval would write");
        names += (names.empty() ? "" : ",") + h;
    }
    if (ndf < 0 || mu < 0)
        throw input_error(in.source + ": header must have columns 'ndf' and 'mu' (got: " + names + ")");
    return {static_cast<std::size_t>(ndf), static_cast<std::size_t>(mu)};
}

// A row evaluated: its fields, its NDF (owned by the cache) and the values.
struct Row {
    const std::vector<std::string>* fields;
    const AnyNdf* ndf;
    evaluation::LambdaG1 values;
};

// Every row evaluated, each NDF prepared on the first row that names its spec (rows usually repeat a handful).
// A bad row is reported on stderr with its line; the count of them is returned in `bad`.
struct Evaluated {
    std::map<std::string, evaluation::Prepared> cache;
    std::vector<AnyNdf> ndfs;  // in order of first appearance: the parameter columns' order
    std::vector<Row> rows;
    int bad = 0;
};

void evaluate_rows(const Input& in, Columns col, const NdfRegistry& registry, const evaluation::Route& route,
                   Evaluated& e) {
    const std::size_t width = in.records.front().fields.size(), n = in.records.size() - 1;
    for (std::size_t i = 1; i < in.records.size(); ++i) {
        const CsvRecord& rec = in.records[i];
        try {
            if (!rec.error.empty()) throw input_error(rec.error);
            if (rec.fields.size() != width)
                throw input_error("expected " + std::to_string(width) + " fields, got " +
                                  std::to_string(rec.fields.size()));
            const std::string& spec = rec.fields[col.ndf];
            auto it = e.cache.find(spec);
            if (it == e.cache.end()) {
                it = e.cache.emplace(spec, prepare(spec, registry, route)).first;
                e.ndfs.push_back(it->second.ndf);
            }
            const double mu = parse_number(rec.fields[col.mu], "mu");
            e.rows.push_back(
                {&rec.fields, &it->second.ndf, evaluation::lambda_g1(it->second, mu, route.options.downward)});
        } catch (const std::exception& x) {  // bad input, or a numeric failure on this row's values
            std::cerr << in.source << ":" << rec.line << ": " << x.what() << "\n";
            ++e.bad;
        }
        if (n >= 2000 && i % (n / 10) == 0) std::cerr << "eval: " << i << "/" << n << " rows\n";
    }
}

// The input's columns, then one per NDF parameter the input has not already, then lambda and g1.
std::string table(const std::vector<std::string>& head, const Evaluated& e) {
    const output::NdfColumns params = output::ndf_columns(e.ndfs, head);
    std::ostringstream out;
    std::vector<std::string> header = head;
    header.insert(header.end(), params.names.begin(), params.names.end());
    header.push_back("lambda");
    header.push_back("g1");
    write_csv_record(out, header);
    for (const Row& r : e.rows) {
        std::vector<std::string> row = *r.fields;
        const std::vector<std::string> cells = params.cells(*r.ndf);
        row.insert(row.end(), cells.begin(), cells.end());
        row.push_back(format_g17(r.values.lambda));
        row.push_back(format_g17(r.values.g1));
        write_csv_record(out, row);
    }
    return out.str();
}

}  // namespace

int eval_csv(const EvalArgs& a, const NdfRegistry& registry, const evaluation::Route& route) {
    const std::optional<output::OutputTarget> target = csv_target(a.output, {a.input});
    const Input in = read_input(a.input);
    const Columns col = find_columns(in);
    Evaluated e;
    evaluate_rows(in, col, registry, route, e);
    if (e.bad) {
        std::cerr << "smithlab: error: " << e.bad << " bad row(s) in " << in.source << "; no output written\n";
        return exit_bad_input;
    }
    emit(target, table(in.records.front().fields, e));
    return exit_ok;
}

}  // namespace smithlab::cli
