#include "smithlab/fit/diffuse_registry.hpp"

#include <algorithm>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/fit/glsl.hpp"

namespace smithlab::fit {

namespace {

// Lower-case letters, digits and '-', from a letter or digit on, not ending in "-fitted".
bool is_model_name(std::string_view name) {
    constexpr std::string_view fitted = "-fitted";
    auto alnum = [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); };
    if (name.empty() || !alnum(name.front()) || name.ends_with(fitted)) return false;
    return std::all_of(name.begin(), name.end(), [&](char c) { return alnum(c) || c == '-'; });
}

// Why the model's constants are not well declared, or empty.
std::string constants_problem(const DiffuseModel& m) {
    if (m.published.size() != m.parameters.size())
        return std::to_string(m.published.size()) + " published values for " + std::to_string(m.parameters.size()) +
            " constants";
    for (std::size_t i = 0; i < m.parameters.size(); ++i) {
        if (m.parameters[i].empty()) return "constant " + std::to_string(i) + " has no name";
        if (std::find(m.parameters.begin(), m.parameters.begin() + static_cast<std::ptrdiff_t>(i), m.parameters[i]) !=
            m.parameters.begin() + static_cast<std::ptrdiff_t>(i))
            return "constant '" + std::string(m.parameters[i]) + "' named twice";
    }
    if (!m.ranges.empty() && m.ranges.size() != m.parameters.size())
        return std::to_string(m.ranges.size()) + " ranges for " + std::to_string(m.parameters.size()) + " constants";
    return {};
}

}  // namespace

void DiffuseRegistry::add(DiffuseModel model) {
    const std::string name(model.name);
    if (!is_model_name(model.name))
        throw input_error(
            "cannot register diffuse model '" + name +
            "' (a name is lower-case letters, digits and '-', from a letter or digit on, not ending in -fitted)");
    if (find(model.name)) throw input_error("diffuse model '" + name + "' is already registered");
    for (const DiffuseModel& m : models_)
        if (glsl_identifier(m.name) == glsl_identifier(model.name))
            throw input_error("diffuse model '" + name + "' has the GLSL name of '" + std::string(m.name) + "'");
    std::string problem = model.source.empty() ? "no source" : model.f == nullptr ? "no f" : constants_problem(model);
    if (problem.empty()) problem = glsl_transcription_problem(model);
    if (!problem.empty()) throw input_error("cannot register diffuse model '" + name + "': " + problem);
    models_.push_back(std::move(model));
}

const DiffuseModel* DiffuseRegistry::find(std::string_view name) const {
    for (const DiffuseModel& m : models_)
        if (m.name == name) return &m;
    return nullptr;
}

const DiffuseModel& DiffuseRegistry::at(std::string_view name) const {
    if (const DiffuseModel* m = find(name)) return *m;
    throw input_error("unknown diffuse model '" + std::string(name) + "' (known: " + names() + ")");
}

std::string DiffuseRegistry::names() const {
    std::string out;
    for (const DiffuseModel& m : models_) out += (out.empty() ? "" : ", ") + std::string(m.name);
    return out;
}

}  // namespace smithlab::fit
