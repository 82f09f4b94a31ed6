// Output helpers shared by the subcommands.
#include <filesystem>
#include <fstream>

#include "commands.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

void write_atomically(const std::string& path, const std::string& text) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp = target.parent_path() / (target.filename().string() + ".partial");
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw input_error("cannot write output file '" + path + "'");
        out << text;
        out.close();
        if (!out) {
            fs::remove(tmp);
            throw input_error("cannot write output file '" + path + "'");
        }
    }
    fs::rename(tmp, target);
}

}  // namespace smithlab::cli
