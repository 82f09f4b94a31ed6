// Parsing of option values, reading of scene files, and the options shared by the subcommands.
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/commands.hpp"
#include "scene/limits.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

double parse_number(const std::string& text, const std::string& what) {
    const double v = parse_double(text, what);
    if (std::isnan(v)) throw input_error(what + " is NaN");
    return v;
}

CLI::Validator strict_real() {
    return CLI::Validator(
        [](std::string& text) {
            try {
                if (std::isnan(parse_double(text, "the value"))) return std::string("the value is NaN");
            } catch (const input_error& e) {
                return std::string(e.what());
            }
            return std::string();
        },
        "", "strict real");
}

CLI::Validator strict_integer() {
    return CLI::Validator(
        [](std::string& text) {
            long long v = 0;
            const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
            const auto [end, ec] = std::from_chars(first, text.data() + text.size(), v);
            if (ec == std::errc::result_out_of_range)
                return "the value is out of range: at most 9223372036854775807 in magnitude, got '" + text + "'";
            if (ec != std::errc() || end != text.data() + text.size() || text.empty())
                return "the value is not a decimal integer: '" + text + "'";
            text = std::to_string(v);  // decimal: CLI11 would read 010 as octal
            return std::string();
        },
        "", "strict integer");
}

std::string read_scene_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw input_error("scene file '" + path + "' is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw input_error("cannot open scene file '" + path + "': " + std::strerror(errno));
    // At most one byte past the cap: /dev/zero, an endless pipe or a huge file is refused without being held.
    std::string text(scene::max_scene_bytes + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) throw input_error("cannot read scene file '" + path + "'");
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > scene::max_scene_bytes)
        throw input_error("scene file '" + path + "' is larger than " + std::to_string(scene::max_scene_bytes) +
                          " bytes (1 MiB), the most a scene file may hold");
    return text;
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
    return command.add_option("--threads", threads, "threads (0: all cores)")
        ->capture_default_str()
        ->check(strict_integer());
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

void add_limit_options(CLI::App& command, scene::SizeLimits& limits) {
    command
        .add_option("--max-cells", limits.max_cells,
                    "the most cells a scene may hold, [brdf] bins counted (inf: no limit)")
        ->capture_default_str()
        ->check(strict_real());
    add_max_walks_option(command, limits);
}

void add_max_walks_option(CLI::App& command, scene::SizeLimits& limits) {
    command.add_option("--max-walks", limits.max_walks, "the most walks a scene may trace in all (inf: no limit)")
        ->capture_default_str()
        ->check(strict_real());
}

void add_scene_options(CLI::App& command, std::string& scene, bool& print_scene, double& scale,
                       const std::string& none) {
    command.add_option("scene", scene, "scene file (TOML); none: " + none);
    command.add_flag("--print-scene", print_scene, "print the default scene (every key documented) and exit");
    command
        .add_option("--scale", scale,
                    "the scene's walks and samples times F (below 1 its tables' axes times sqrt(F)), in (0, 1000] "
                    "(0.01: a quick run of the same scene)")
        ->capture_default_str()
        ->check(strict_real());
}

void require_scale(double scale) { require(scale > 0.0 && scale <= 1000.0, "--scale", "in (0, 1000]", scale); }

}  // namespace smithlab::cli
