#include "fit/fit_shaders.hpp"

#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "output/staged_directory.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/glsl.hpp"

namespace smithlab::fit {

void write_shaders(const std::filesystem::path& dir, const Results& results) {
    std::vector<fit::ShaderModel> models;
    for (std::size_t n = 0; n < results.data.size(); ++n)
        for (const Measured& m : results.fits[n])
            models.push_back({m.name, results.data[n].label, m.model, m.params, m.stderr_});
    // Two labels that sanitize alike ("a.b" and "apb") would share a function and a file, and a name could be a
    // helper's: refused, naming the model. A model without GLSL gets a line in models.glsl saying so, and no file.
    const std::string helpers = fit::glsl_helpers(models);
    std::set<std::string> names;
    for (const fit::ShaderModel& m : models)
        if (const std::string name = fit::glsl_function_name(m);
            !names.insert(name).second || helpers.find(" " + name + "(") != std::string::npos)
            throw input_error("model '" + std::string(m.name) + "' on '" + std::string(m.ndf) +
                              "' has the GLSL name of another (" + fit::glsl_function_name(m) + ")");
    output::write_file(dir / "models.glsl", fit::glsl_library(models));
    std::filesystem::create_directories(dir / "brdf");
    for (const fit::ShaderModel& m : models)
        if (m.model->glsl.get())
            output::write_file(
                dir / "brdf" / (fit::glsl_identifier(m.name) + "-" + fit::glsl_identifier(m.ndf) + ".brdf"),
                fit::brdf_explorer_file(m, helpers));
}

}  // namespace smithlab::fit
