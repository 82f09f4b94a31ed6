// Output helpers shared by the subcommands.
#include <filesystem>
#include <fstream>

#include "commands.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp = target.parent_path() / (target.filename().string() + ".partial");
    try {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw input_error("cannot write output file '" + path + "'");
        write(out);
        out.close();
        if (!out) throw input_error("cannot write output file '" + path + "'");
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
    fs::rename(tmp, target);
}

void write_atomically(const std::string& path, const std::string& text) {
    write_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace smithlab::cli
