#include "compensation/tables_scene.hpp"

#include <limits>

#include "scene/strict_table.hpp"

namespace smithlab::compensation {

TablesScene parse_tables_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                               const scene::SizeLimits& limits) {
    const toml::value data = scene::parse_toml(text, source);
    scene::StrictTable doc(data, source, "", {"title", "seed", "ndf", "compensation"});
    TablesScene s;
    s.title = doc.text("title", s.title);
    s.seed = static_cast<std::uint64_t>(doc.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));
    s.ndfs = scene::read_alpha_families(doc, registry, "the tables sweep alpha over compensation.alpha");
    s.compensation = read_settings(doc, s.ndfs, 0.0, registry, limits);
    if (!s.compensation.enabled)
        doc.fail("compensation", "is missing: a tables scene tabulates what its [compensation] table asks for");
    doc.done();
    return s;
}

}  // namespace smithlab::compensation
