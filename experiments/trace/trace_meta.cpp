#include "trace/trace_meta.hpp"

#include <sstream>
#include <toml.hpp>

#include "smithlab/csv.hpp"

namespace smithlab::trace {

namespace {

std::string toml_string(const std::string& s) { return toml::format(toml::value(s)); }

std::string toml_list(const std::vector<double>& v) {
    std::string out = "[";
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_shortest(v[i]);
    return out + "]";
}

nlohmann::ordered_json cells_json(const std::vector<CellMeta>& cells) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const CellMeta& c : cells)
        list.push_back({{"cell", c.index},
                        {"ndf", c.ndf},
                        {"material", c.material},
                        {"theta_i", c.theta_i},
                        {"phi_i", c.phi_i},
                        {"bounces", c.bounces},
                        {"capped_walks", c.capped_walks}});
    return list;
}

}  // namespace

std::string format_trace_scene(const TraceScene& s) {
    std::ostringstream t;
    t << "title = " << toml_string(s.title) << "\nmaterials = [";
    for (std::size_t i = 0; i < s.materials.size(); ++i) t << (i ? ", " : "") << toml_string(s.materials[i]);
    t << "]\n\n[walks]\nn = " << s.walks << "\nseed = " << s.seed << "\nmax_order = " << s.max_order
      << "\ndownward = " << toml_string(s.downward) << "\nhit_normal = " << toml_string(s.hit_normal)
      << "\n\n[grid]\ntheta_i = " << toml_list(s.theta_i) << "\nphi_i = " << toml_list(s.phi_i) << "\n";
    for (const SceneNdf& n : s.ndfs) t << "\n[[ndf]]\nspec = " << toml_string(n.spec) << "\n";
    if (!s.brdf.empty()) t << "\n[brdf]\ntheta_bins = " << s.brdf.n_theta << "\nphi_bins = " << s.brdf.n_phi << "\n";
    return t.str();
}

nlohmann::ordered_json trace_meta(const TraceScene& s, const std::string& source, const RunMeta& run) {
    return {{"title", s.title},
            {"source", source},
            {"scene", format_trace_scene(s)},
            {"version", SMITHLAB_VERSION},
            {"seed", s.seed},
            {"walks", s.walks},
            {"max_order", s.max_order},
            {"downward", s.downward},
            {"hit_normal", s.hit_normal},
            {"cells", cells_json(run.cells)},
            {"cells_traced", run.traced},
            {"cells_reused", run.reused},
            {"bounces", run.bounces},
            {"seconds", run.seconds},
            {"threads", run.threads}};
}

}  // namespace smithlab::trace
