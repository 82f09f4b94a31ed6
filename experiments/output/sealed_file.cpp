#include "output/sealed_file.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

#include "output/output_file.hpp"
#include "smithlab/util/checksum.hpp"

namespace smithlab::output {

void write_sealed(const std::filesystem::path& path, const std::string& body) {
    write_output(resolve_output(path.string()), [&](std::ostream& out) { out << body << util::checksum_line(body); });
}

std::optional<std::string> read_sealed(const std::filesystem::path& path, const std::string& name) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return std::nullopt;
    std::ostringstream whole;
    whole << file.rdbuf();
    const std::string text = whole.str();
    const std::optional<std::string_view> body = util::unseal(text);
    if (!body) {
        std::fprintf(stderr, "%s: checksum mismatch, traced again\n", name.c_str());
        return std::nullopt;
    }
    return std::string(*body);
}

}  // namespace smithlab::output
