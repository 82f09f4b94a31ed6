// The diffuse models as GLSL (fit/glsl.hpp), from the transcription each model carries (DiffuseModel::glsl, each
// built-in model's in its file in fit/diffuse/) and the common helpers (fit/diffuse/common.hpp).
#include "smithlab/fit/glsl.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/diffuse/common.hpp"

namespace smithlab::fit {

namespace {

// The common helpers' constants, as literals (glsl_float), then their functions.
std::string common_helpers() {
    return "const float smithlab_pi = " + glsl_float(common::pi) + ";\n" +
        "const float smithlab_inv_pi = " + glsl_float(common::inv_pi) + ";\n" +
        "// EON's constants (the paper's constant1_FON and constant2_FON): A = 1/(1 + c1 r), <E_F> = A (1 + c2 r).\n"
        "const float smithlab_eon_c1 = " +
        glsl_float(common::eon_c1) + ";  // 1/2 - 2/(3 pi)\n" +
        "const float smithlab_eon_c2 = " + glsl_float(common::eon_c2) + ";  // 2/3 - 28/(15 pi)\n" + "\n" +
        std::string(common::glsl_functions);
}

// A call's text and placeholders in order: text(piece) for the text between them, constant(i) for each {i}. The index
// of a brace that opens no {digits}, or nothing where all are well formed.
template <class Text, class Constant>
std::optional<std::size_t> walk_call(std::string_view call, Text&& text, Constant&& constant) {
    std::size_t from = 0;
    for (std::size_t open = call.find('{'); open != std::string_view::npos; open = call.find('{', from)) {
        const std::size_t close = call.find('}', open);
        const std::string_view digits =
            close == std::string_view::npos ? std::string_view{} : call.substr(open + 1, close - open - 1);
        if (digits.empty() || digits.size() > 3 ||
            !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return open;
        text(call.substr(from, open - from));
        constant(static_cast<std::size_t>(std::stoul(std::string(digits))));
        from = close + 1;
    }
    text(call.substr(from));
    return std::nullopt;
}

// The function a call starts with: the identifier before its first '(' (empty where it does not start so).
std::string_view called_function(std::string_view call) {
    const std::size_t paren = call.find('(');
    const std::string_view name = call.substr(0, paren == std::string_view::npos ? 0 : paren);
    const bool identifier = !name.empty() && !(name.front() >= '0' && name.front() <= '9') &&
        std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        });
    return identifier ? name : std::string_view{};
}

// The call of m's function at m's constants.
std::string call_of(const ShaderModel& m) {
    const DiffuseModel& model = *m.model;
    const Glsl* glsl = model.glsl.get();
    if (!glsl) throw input_error("diffuse model '" + std::string(model.name) + "' has no GLSL transcription");
    if (m.constants.size() != model.parameters.size())
        throw input_error("GLSL of '" + std::string(m.name) + "': " + std::to_string(m.constants.size()) +
                          " constants for " + std::to_string(model.parameters.size()) + " parameters");
    if (const std::string problem = glsl_transcription_problem(model); !problem.empty())
        throw input_error("diffuse model '" + std::string(model.name) + "': " + problem);
    std::string out;
    walk_call(
        glsl->call, [&](std::string_view text) { out += text; },
        [&](std::size_t i) { out += glsl_float(m.constants[i]); });
    return out;
}

// Text for a // comment: printable ASCII only (GLSL 3.30's character set), anything else as '?'.
std::string line_comment_text(std::string_view text) {
    std::string out(text);
    for (char& c : out)
        if (c < ' ' || c > '~') c = '?';
    return out;
}

std::string format_g(double v, int digits) { return format_printf("%.*g", digits, v); }

}  // namespace

std::string glsl_identifier(std::string_view text) {
    std::string out;
    bool gap = false;
    for (const char c : text) {
        const char lower = c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
        if ((lower >= 'a' && lower <= 'z') || (lower >= '0' && lower <= '9') || lower == '.') {
            if (gap && !out.empty()) out += '_';
            out += lower == '.' ? 'p' : lower;
            gap = false;
        } else {
            gap = true;
        }
    }
    if (out.empty()) throw input_error("'" + std::string(text) + "' has no letter or digit to name a GLSL function");
    return out;
}

std::string glsl_function_name(const ShaderModel& m) {
    return "smithlab_" + glsl_identifier(m.name) + "_" + glsl_identifier(m.ndf);
}

std::string glsl_float(double v) {
    if (!std::isfinite(v)) throw input_error("a GLSL constant must be finite, got " + format_g(v, 17));
    std::string s = format_g(v, 9);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return std::signbit(v) ? "(" + s + ")" : s;
}

std::string glsl_transcription_problem(const DiffuseModel& m) {
    const Glsl* glsl = m.glsl.get();
    if (!glsl) return {};
    const std::string_view function = called_function(glsl->call);
    if (function.empty())
        return "its GLSL call '" + std::string(glsl->call) + "' does not start with a function's name";
    const std::string definition = "float " + std::string(function) + "(";
    bool defined = common::glsl_functions.find(definition) != std::string_view::npos;
    for (std::string_view f : glsl->functions) defined = defined || f.find(definition) != std::string_view::npos;
    if (!defined)
        return "its GLSL calls " + std::string(function) + ", which neither its functions nor the common ones define";
    std::vector<bool> used(m.parameters.size(), false);
    std::string problem;
    const auto bad = walk_call(
        glsl->call, [](std::string_view) {},
        [&](std::size_t i) {
            if (i < used.size()) used[i] = true;
            else if (problem.empty())
                problem = "its GLSL call names {" + std::to_string(i) + "}, not one of its constants";
        });
    if (bad) return "a brace at " + std::to_string(*bad) + " of its GLSL call opens no {i}";
    for (std::size_t i = 0; i < used.size() && problem.empty(); ++i)
        if (!used[i])
            problem =
                "its GLSL call leaves out constant {" + std::to_string(i) + "} (" + std::string(m.parameters[i]) + ")";
    return problem;
}

std::string glsl_helpers(std::span<const ShaderModel> models) {
    std::string out = common_helpers();
    std::vector<std::string_view> written;
    for (const ShaderModel& m : models)
        if (const Glsl* glsl = m.model->glsl.get())
            for (std::string_view f : glsl->functions)
                if (std::find(written.begin(), written.end(), f) == written.end()) {
                    written.push_back(f);
                    out += "\n";
                    out += f;
                }
    return out;
}

std::string glsl_function(const ShaderModel& m) {
    const DiffuseModel& model = *m.model;
    const std::string call = call_of(m);  // refuses a model without GLSL, or the wrong number of constants
    std::string out = "// " + line_comment_text(m.name) + " on " + line_comment_text(m.ndf) + ": " +
        line_comment_text(model.source) + "\n";
    if (model.parameters.empty()) {
        out += "// no free constants\n";
    } else {
        out += m.stderrs.empty() ? "// constants at their published values (not fitted):"
                                 : "// constants fitted (value +- standard error):";
        for (std::size_t i = 0; i < model.parameters.size(); ++i) {
            out += (i ? ", " : " ") + std::string(model.parameters[i]) + " = " + format_g(m.constants[i], 9);
            if (i < m.stderrs.size()) out += " +- " + format_g(m.stderrs[i], 3);
        }
        out += "\n";
    }
    out += "float " + glsl_function_name(m) + "(vec3 L, vec3 V, vec3 N, float alpha, float albedo)\n{\n    return " +
        call + ";\n}\n";
    return out;
}

std::string glsl_library(std::span<const ShaderModel> models) {
    std::string out =
        "// smithlab's diffuse models at the constants `smithlab fit` measured, transcribed from\n"
        "// lib/src/fit/diffuse_models.cpp. One function per model and NDF family:\n"
        "//     float smithlab_<model>_<ndf>(vec3 L, vec3 V, vec3 N, float alpha, float albedo)\n"
        "// returns the BRDF f without the cosine; L toward the light, V toward the viewer, N the normal, unit\n"
        "// vectors with dot(N, L) > 0 and dot(N, V) > 0 (not checked); alpha the GGX roughness (Disney's roughness\n"
        "// squared), albedo in [0, 1]. GLSL 3.30, no extensions, no #version line.\n\n";
    out += glsl_helpers(models);
    for (const ShaderModel& m : models) {
        out += '\n';
        out += m.model->glsl.get() ? glsl_function(m)
                                   : "// " + line_comment_text(m.name) + " on " + line_comment_text(m.ndf) +
                ": no GLSL transcription (the model has none)\n";
    }
    return out;
}

std::string brdf_explorer_file(const ShaderModel& m, std::string_view helpers) {
    const std::string function = glsl_function(m);
    std::string out = "analytic\n\n";
    out += "# smithlab: " + line_comment_text(m.name) + " on " + line_comment_text(m.ndf) +
        ", the diffuse BRDF (no cosine).\n";
    out += "# " + line_comment_text(m.model->source) + "\n";
    out +=
        "# [type] [name] [min val] [max val] [default val]\n"
        "::begin parameters\n"
        "float albedo 0 1 0.75\n"
        "float alpha 0.001 1 0.25\n"
        "::end parameters\n\n"
        "::begin shader\n\n";
    out += std::string(helpers) + "\n" + function + "\n";
    out +=
        "// smithlab's models hold for L and V above the surface only: 0 below it, as Disney's disney.brdf does.\n"
        "vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )\n{\n"
        "    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);\n"
        "    return vec3(" +
        glsl_function_name(m) +
        "(L, V, N, alpha, albedo));\n}\n\n"
        "::end shader\n";
    return out;
}

}  // namespace smithlab::fit
