// smithlab list: the registered NDFs, their parameters, descriptions and example specs; the facet materials; the
// diffuse models' names.
#include <iostream>

#include "cli/commands.hpp"

namespace smithlab::cli {

CLI::App* add_list(CLI::App& app) {
    return app.add_subcommand(
        "list",
        "List the registered NDFs, their parameters and example specs, the facet materials, and the diffuse "
        "models' names");
}

int run_list(const NdfRegistry& registry) {
    const fit::DiffuseRegistry& models = registry.diffuse_models();
    for (const NdfInfo* info : registry.list()) {
        std::cout << info->name << "(";
        for (std::size_t i = 0; i < info->parameters.size(); ++i) std::cout << (i ? ", " : "") << info->parameters[i];
        for (std::size_t i = 0; i < info->text_parameters.size(); ++i)
            std::cout << (i || !info->parameters.empty() ? ", " : "") << info->text_parameters[i];
        std::cout << ")\n    " << info->description << "\n";
        if (info->examples.empty()) continue;  // a family read from a file has none to offer
        std::cout << "    e.g.";
        for (const auto& ex : info->examples) std::cout << "  " << ex;
        std::cout << "\n";
    }
    std::cout << "diffuse models (smithlab fit --list-models): ";
    for (const fit::DiffuseModel& m : models.list())
        std::cout << (&m == &models.list().front() ? "" : ", ") << m.name << (m.glsl.get() ? "" : " (no GLSL)");
    std::cout << "\n";
    std::cout << "\nFacet materials (--material, a scene's material):\n";
    for (const walk::MaterialInfo* info : registry.materials().list())
        std::cout << info->spec() << "\n    " << info->description << "\n";
    return exit_ok;
}

}  // namespace smithlab::cli
