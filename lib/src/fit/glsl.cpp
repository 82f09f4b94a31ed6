// The diffuse models as GLSL (fit/glsl.hpp). Each helper below transcribes the C++ function of the same name in
// fit/diffuse_models.cpp line for line (same clamps, same guards against 0/0, same order of operations), with
// (L, V, N) for (wi, wo, z): wi.z() -> dot(N, L), the tangential part (x, y) -> L - dot(N, L) N. Where a C++ value
// has no float counterpart the substitute is named where it is used (Chan's 1e-300 floor).
#include "smithlab/fit/glsl.hpp"

#include <cmath>
#include <numbers>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::fit {

namespace {

// The helpers' constants, as literals (glsl_float), then the helpers: each model's formula in its own parameters.
std::string helper_constants() {
    constexpr double pi = std::numbers::pi;
    return "const float smithlab_pi = " + glsl_float(pi) + ";\n" +
        "const float smithlab_inv_pi = " + glsl_float(std::numbers::inv_pi) + ";\n" +
        "// EON's constants (the paper's constant1_FON and constant2_FON): A = 1/(1 + c1 r), <E_F> = A (1 + c2 r).\n"
        "const float smithlab_eon_c1 = " +
        glsl_float(0.5 - 2.0 / (3.0 * pi)) + ";  // 1/2 - 2/(3 pi)\n" +
        "const float smithlab_eon_c2 = " + glsl_float(2.0 / 3.0 - 28.0 / (15.0 * pi)) + ";  // 2/3 - 28/(15 pi)\n";
}

constexpr std::string_view helper_functions = R"(
float smithlab_pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

// s = L.V - (N.L)(N.V) = cos(phi) sin(theta_i) sin(theta_o), from the tangential components: no cancellation.
float smithlab_tangential_dot(vec3 L, vec3 V, vec3 N)
{
    return dot(L - dot(N, L) * N, V - dot(N, V) * N);
}

// Fujii's s/t (and EON's): s where s <= 0, else s / max(N.L, N.V) (= cos(phi) sin(alpha') tan(beta)).
float smithlab_s_over_t(vec3 L, vec3 V, vec3 N)
{
    float s = smithlab_tangential_dot(L, V, N);
    return s > 0.0 ? s / max(dot(N, L), dot(N, V)) : s;
}

// G(mu) of EON's E_F, with (S/mu)(1 - S^3) = S mu (1 + S + S^2)/(1 + S): no 0/0 at grazing.
float smithlab_eon_g(float mu)
{
    float m = clamp(mu, 0.0, 1.0);
    float s = sqrt((1.0 - m) * (1.0 + m));
    return s * (acos(m) - s * m) + (2.0 / 3.0) * (s * m * (1.0 + s + s * s) / (1.0 + s) - s);
}

// EON's rho_ms = rho^2 <E_F> / (1 - rho (1 - <E_F>)).
float smithlab_eon_rho_ms(float r, float albedo)
{
    float avg = (1.0 + smithlab_eon_c2 * r) / (1.0 + smithlab_eon_c1 * r);
    return albedo * albedo * avg / (1.0 - albedo * (1.0 - avg));
}

// Lambert: albedo / pi.
float smithlab_lambert(float albedo)
{
    return albedo * smithlab_inv_pi;
}

// Burley 2012, Physically-Based Shading at Disney, sec. 5.3: albedo/pi (1 + (FD90 - 1)(1 - cos_l)^5)
// (1 + (FD90 - 1)(1 - cos_v)^5), FD90 = 0.5 + 2 r cos^2(theta_d), cos^2(theta_d) = |L + V|^2 / 4.
float smithlab_disney_diffuse(vec3 L, vec3 V, vec3 N, float perceptual_roughness, float albedo)
{
    float cos2_d = 0.25 * dot(L + V, L + V);
    float fd90_minus_1 = 2.0 * perceptual_roughness * cos2_d - 0.5;
    float fl = 1.0 + fd90_minus_1 * smithlab_pow5(1.0 - dot(N, L));
    float fv = 1.0 + fd90_minus_1 * smithlab_pow5(1.0 - dot(N, V));
    return albedo * smithlab_inv_pi * (fl * fv);
}

// Oren and Nayar 1994, Generalization of Lambert's Reflectance Model, the full model: L1 (C1, C2, C3) plus the
// interreflection term L2, sigma the facets' slope-angle deviation (radians); alpha' = max(theta_i, theta_o) and
// beta = min from their sines and cosines; max(0, f) (it dips below 0 at sigma >~ 0.7, both grazing, forward).
float smithlab_oren_nayar(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float s2 = sigma * sigma;
    float cos_i = dot(N, L), cos_o = dot(N, V);
    vec3 Lt = L - cos_i * N, Vt = V - cos_o * N;
    float ri = length(Lt), ro = length(Vt);
    float sin_a = max(ri, ro), sin_b = min(ri, ro);
    float cos_a = min(cos_i, cos_o), cos_b = max(cos_i, cos_o);
    float a = atan(sin_a, cos_a), b = atan(sin_b, cos_b);
    float tan_b = sin_b / cos_b, tan_half_sum = (sin_a + sin_b) / (cos_a + cos_b);
    // cos(phi) is undefined with either direction along N, where every term it multiplies vanishes: 0 there.
    float rr = ri * ro;
    float cos_phi = rr > 0.0 ? clamp(dot(Lt, Vt) / rr, -1.0, 1.0) : 0.0;
    float b2 = 2.0 * b / smithlab_pi;
    float c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    float c2 = 0.45 * s2 / (s2 + 0.09) * (cos_phi >= 0.0 ? sin_a : sin_a - b2 * b2 * b2);
    float c3_root = 4.0 * a * b / (smithlab_pi * smithlab_pi), c3 = 0.125 * s2 / (s2 + 0.09) * c3_root * c3_root;
    float l1 = c1 + cos_phi * c2 * tan_b + (1.0 - abs(cos_phi)) * c3 * tan_half_sum;
    float l2 = 0.17 * albedo * s2 / (s2 + 0.13) * (1.0 - cos_phi * b2 * b2);
    return max(0.0, albedo * smithlab_inv_pi * (l1 + l2));
}

// Oren and Nayar 1994, the qualitative model: albedo/pi (A + B max(0, cos(phi)) sin(alpha') tan(beta)).
float smithlab_oren_nayar_qualitative(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float s2 = sigma * sigma;
    float a = 1.0 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    float s = max(0.0, smithlab_tangential_dot(L, V, N));
    return albedo * smithlab_inv_pi * (a + b * (s / max(dot(N, L), dot(N, V))));
}

// Fujii 2013, A tiny improvement of Oren-Nayar reflectance model: albedo/pi (A + B s/t), A = 1/(1 + c1 sigma),
// B = sigma A; max(0, f) (smithlab's guard, not Fujii's).
float smithlab_fujii(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float a = 1.0 / (1.0 + smithlab_eon_c1 * sigma), b = sigma * a;
    return max(0.0, albedo * smithlab_inv_pi * (a + b * smithlab_s_over_t(L, V, N)));
}

// Portsmouth, Kutz and Hill 2025, EON, JCGT 14(1): the FON lobe plus rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) /
// (1 - <E_F>), the factor A r of 1 - E_F cancelled against 1 - <E_F> = A r (c1 - c2): no 0/0 at r = 0.
float smithlab_eon(vec3 L, vec3 V, vec3 N, float r, float albedo)
{
    float a = 1.0 / (1.0 + smithlab_eon_c1 * r);
    float f_ss = albedo * smithlab_inv_pi * a * (1.0 + r * smithlab_s_over_t(L, V, N));
    float one_minus_i = max(0.0, smithlab_eon_c1 - smithlab_eon_g(dot(N, L)) * smithlab_inv_pi);
    float one_minus_o = max(0.0, smithlab_eon_c1 - smithlab_eon_g(dot(N, V)) * smithlab_inv_pi);
    float f_ms = smithlab_eon_rho_ms(r, albedo) * smithlab_inv_pi * (a * r) * (one_minus_i * one_minus_o) /
                 (smithlab_eon_c1 - smithlab_eon_c2);
    return max(0.0, f_ss) + f_ms;
}

// Chan 2018, Material Advances in Call of Duty: WWII, as Unreal Engine 5's BRDF.ush Diffuse_Chan (a2 = alpha^2).
float smithlab_chan_2018(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float retro_weight)
{
    vec3 sum = L + V;
    float len = length(sum);
    float voh = clamp(0.5 * len, 0.0, 1.0);
    float noh = clamp((dot(N, L) + dot(N, V)) / len, 0.0, 1.0);
    float nol = clamp(dot(N, L), 0.0, 1.0), nov = clamp(dot(N, V), 0.0, 1.0);
    // 2/a2 - 1 kept positive so that alpha > sqrt(2) reads as g = 0, not NaN: the C++ floors it at 1e-300, below
    // float's range; float's smallest normal gives the same g (0).
    float a2 = alpha * alpha;
    float g = clamp(log2(max(2.0 / a2 - 1.0, 1.17549435e-38)) / 18.0, 0.0, 1.0);
    float f0 = voh + smithlab_pow5(1.0 - voh);
    float fdv = 1.0 - 0.75 * smithlab_pow5(1.0 - nov), fdl = 1.0 - 0.75 * smithlab_pow5(1.0 - nol);
    float t = clamp(2.2 * g - 0.5, 0.0, 1.0);
    float fd = f0 + t * (fdv * fdl - f0);
    float fb = ((34.5 * g - 59.0) * g + 24.5) * voh * exp2(-max(73.2 * g - 21.2, 8.9) * sqrt(noh));
    return albedo * smithlab_inv_pi * (fd + retro_weight * fb);
}

// Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), slide "GGX Diffuse Approximation":
// facing = 0.5 + 0.5 L.V = |L + V|^2 / 4, rough = facing (a - b facing)(c + N.H)/N.H,
// smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5), single = (1/pi) lerp(smooth, rough, alpha). (smooth_k: `smooth`
// is a GLSL keyword.)
float smithlab_hammon_2017_single(vec3 L, vec3 V, vec3 N, float alpha, float rough_a, float rough_b, float rough_c,
                                  float smooth_k)
{
    vec3 sum = L + V;
    float len2 = dot(sum, sum);
    float facing = 0.25 * len2;
    float noh = (dot(N, L) + dot(N, V)) / sqrt(len2);
    float rough = facing * (rough_a - rough_b * facing) * ((rough_c + noh) / noh);
    float smooth_term = smooth_k * ((1.0 - smithlab_pow5(1.0 - dot(N, L))) * (1.0 - smithlab_pow5(1.0 - dot(N, V))));
    return smithlab_inv_pi * (smooth_term + alpha * (rough - smooth_term));
}

// Hammon 2017 read as albedo (single + albedo multi), multi = m alpha.
float smithlab_hammon_2017(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b,
                           float rough_c, float smooth_k, float multi)
{
    float single = smithlab_hammon_2017_single(L, V, N, alpha, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + albedo * (multi * alpha));
}

// Hammon 2017 read as albedo (single + multi), multi = m alpha.
float smithlab_hammon_2017_linear(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b,
                                  float rough_c, float smooth_k, float multi)
{
    float single = smithlab_hammon_2017_single(L, V, N, alpha, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + multi * alpha);
}

// smithlab 2026 (this tool's own family, from the traced data): Hammon's single term blended by t = alpha^p,
// multi = m alpha^q (1 + u (1 - facing)), f = albedo (single + albedo multi).
float smithlab_2026(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b, float rough_c,
                    float smooth_k, float multi, float blend_power, float multi_power, float multi_forward)
{
    float t = pow(alpha, blend_power);
    float facing = 0.25 * dot(L + V, L + V);
    float multi_term = multi * pow(alpha, multi_power) * (1.0 + multi_forward * (1.0 - facing));
    float single = smithlab_hammon_2017_single(L, V, N, t, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + albedo * multi_term);
}
)";

// Each model of diffuse_models() as a call of its helper, as its f_* wrapper in diffuse_models.cpp calls the C++
// function; {i} is the model's i-th constant.
struct Call {
    std::string_view model, call;
};
constexpr Call calls[] = {
    {"lambert", "smithlab_lambert(albedo)"},
    {"disney", "smithlab_disney_diffuse(L, V, N, sqrt(alpha), albedo)"},
    {"oren-nayar", "smithlab_oren_nayar(L, V, N, {0} * alpha, albedo)"},
    {"oren-nayar-sqrt2", "smithlab_oren_nayar(L, V, N, alpha * 1.41421356 * 0.5, albedo)"},  // sqrt(2), 9 digits
    {"oren-nayar-qualitative", "smithlab_oren_nayar_qualitative(L, V, N, 0.5 * alpha, albedo)"},
    {"fujii", "smithlab_fujii(L, V, N, {0} * alpha, albedo)"},
    {"eon", "smithlab_eon(L, V, N, clamp({0} * alpha, 0.0, 1.0), albedo)"},
    {"chan-2018", "smithlab_chan_2018(L, V, N, alpha, albedo, 1.0)"},
    {"hammon-2017", "smithlab_hammon_2017(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4})"},
    {"hammon-2017-linear", "smithlab_hammon_2017_linear(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4})"},
    {"smithlab-2026", "smithlab_2026(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4}, {5}, {6}, {7})"},
};

// The call of m's helper at m's constants.
std::string call_of(const ShaderModel& m) {
    const DiffuseModel& model = *m.model;
    if (m.constants.size() != model.parameters.size())
        throw input_error("GLSL of '" + std::string(m.name) + "': " + std::to_string(m.constants.size()) +
                          " constants for " + std::to_string(model.parameters.size()) + " parameters");
    for (const Call& c : calls) {
        if (c.model != model.name) continue;
        std::string out;
        for (std::size_t i = 0; i < c.call.size(); ++i) {
            const std::size_t close = c.call[i] == '{' ? c.call.find('}', i) : std::string_view::npos;
            if (close != std::string_view::npos) {
                out += glsl_float(m.constants[std::stoul(std::string(c.call.substr(i + 1, close - i - 1)))]);
                i = close;
            } else {
                out += c.call[i];
            }
        }
        return out;
    }
    throw input_error("diffuse model '" + std::string(model.name) + "' has no GLSL transcription (fit/glsl.cpp)");
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

std::string glsl_helpers() { return helper_constants() + std::string(helper_functions); }

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
    out += glsl_helpers();
    for (const ShaderModel& m : models) {
        out += '\n';
        out += glsl_function(m);
    }
    return out;
}

std::string brdf_explorer_file(const ShaderModel& m) {
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
    out += glsl_helpers() + "\n" + function + "\n";
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
