// Parsing of option values, reading of scene files, and the options shared by the subcommands.
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/commands.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

double parse_number(const std::string& text, const std::string& what) {
    const double v = parse_double(text, what);
    if (std::isnan(v)) throw input_error(what + " is NaN");
    return v;
}

std::string read_scene_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw input_error("scene file '" + path + "' is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw input_error("cannot open scene file '" + path + "': " + std::strerror(errno));
    std::stringstream text;
    text << in.rdbuf();
    if (in.bad()) throw input_error("cannot read scene file '" + path + "'");
    return text.str();
}

unsigned long long parse_seed(const std::string& text, const std::string& what) {
    errno = 0;
    const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
    if (!digits || errno == ERANGE)
        throw input_error(what + " must be an integer in [0, 18446744073709551615], got '" + text + "'");
    return v;
}

void add_backend_option(CLI::App& command, std::string& backend) {
    command.add_option("--backend", backend, "quadrature backend: " + join_names(backend_names, " | ", " | "))
        ->capture_default_str()
        ->check(CLI::IsMember(names_of(backend_names)));
}

CLI::Option* add_output_option(CLI::App& command, std::string& output, const std::string& what) {
    return command.add_option("-o,--output", output, what);
}

CLI::Option* add_threads_option(CLI::App& command, int& threads) {
    return command.add_option("--threads", threads, "threads (0: all cores)")->capture_default_str();
}

void require_threads(int threads) { require(threads >= 0, "--threads", ">= 0 (0: all cores)", threads); }

CLI::Option* add_seed_option(CLI::App& command, std::string& seed) {
    return command.add_option("--seed", seed, "seed, an integer in [0, 2^64)")->capture_default_str();
}

CLI::Option* add_downward_option(CLI::App& command, std::string& downward) {
    return command
        .add_option("--downward", downward, "Lambda for mu < 0: " + join_described(downward_names, " | ", " | "))
        ->capture_default_str()
        ->check(CLI::IsMember(names_of(downward_names)));
}

void add_scene_options(CLI::App& command, std::string& scene, bool& print_scene, const std::string& none) {
    command.add_option("scene", scene, "scene file (TOML); none: " + none);
    command.add_flag("--print-scene", print_scene, "print the default scene (every key documented) and exit");
}

}  // namespace smithlab::cli
