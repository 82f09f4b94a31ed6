// The worked example of docs/extending.md, "A new scene key": a table of a scene read strictly through
// scene/strict_table.hpp, the reader of every scene format. docs/update_docs.py quotes the parts between the
// [docs: ...] markers into docs/extending.md (ctest docs_up_to_date fails when they differ).
#include <catch2/catch.hpp>
#include <cstdint>
#include <smithlab/errors.hpp>
#include <string>

#include "scene/strict_table.hpp"

// [docs: scene-key]
// An optional [exposure] table with two keys: `stops` (a real, default 0) and `samples` (an integer in [1, 1e6],
// default 16). Every key is declared where the table is opened; each getter checks the type and marks the key read.
struct Exposure {
    double stops = 0.0;
    std::int64_t samples = 16;
};

Exposure read_exposure(smithlab::scene::StrictTable& doc) {
    Exposure e;
    if (auto t = doc.optional_table("exposure", {"stops", "samples"})) {
        e.stops = t->real("stops", e.stops);
        e.samples = t->integer("samples", 1, 1'000'000, e.samples);
        t->done();  // a declared key that was given but never read is a bug in this reader: refused
    }
    return e;
}
// [end docs]

namespace {

// A scene document with the keys "title" and "exposure", read as scene.toml.
Exposure read_scene(const std::string& text) {
    const toml::value data = smithlab::scene::parse_toml(text, "scene.toml");
    smithlab::scene::StrictTable doc(data, "scene.toml", "", {"title", "exposure"});
    doc.text("title", "");
    const Exposure e = read_exposure(doc);
    doc.done();
    return e;
}

}  // namespace

// [docs: scene-key-test]
TEST_CASE("a new scene key: read when given and defaulted when absent and refused when wrong", "[extending][scenes]") {
    const Exposure e = read_scene("title = \"t\"\n[exposure]\nstops = 1\nsamples = 64\n");
    CHECK(e.stops == 1.0);  // an integer stands for a real
    CHECK(e.samples == 64);
    CHECK(read_scene("title = \"t\"\n").samples == 16);

    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(read_scene("[exposure]\nstop = 1\n"),
                      Contains("scene.toml:2: unknown key 'exposure.stop' (did you mean 'exposure.stops'?)"));
    CHECK_THROWS_WITH(read_scene("[exposure]\nsamples = 1.5\n"),
                      Contains("scene.toml:2: exposure.samples must be an integer in [1, 1000000], got a real (1.5)"));
    CHECK_THROWS_WITH(read_scene("[exposure]\nsamples = 0\n"), Contains("exposure.samples must be an integer"));
    CHECK_THROWS_WITH(read_scene("[exposur]\n"), Contains("unknown section 'exposur' (did you mean 'exposure'?)"));
}
// [end docs]
