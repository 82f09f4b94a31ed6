// Spec strings, the registry, and the CSV reader.
#include <catch2/catch.hpp>
#include <smithlab/gtr.hpp>
#include <sstream>

using namespace smithlab;

namespace {
std::string message_of(const std::string& spec) {
    try {
        builtin_registry().make(spec);
    } catch (const input_error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST_CASE("spec strings parse, and canonicalize", "[registry]") {
    const auto s = parse_spec("  gtr( alpha = 0.3 ,gamma=1.5 ) ");
    CHECK(s.name == "gtr");
    REQUIRE(s.params.size() == 2);
    CHECK(s.params[1].first == "gamma");
    CHECK(s.params[1].second == 1.5);
    CHECK(builtin_registry().make("gtr(gamma=1.5, alpha=0.3)").spec() == "gtr(alpha=0.3, gamma=1.5)");
    // The canonical spec round-trips every digit.
    const std::string canon = builtin_registry().make("ggx(alpha=0.30000000000000004)").spec();
    CHECK(parse_spec(canon).params[0].second == 0.30000000000000004);
}

TEST_CASE("bad specs: each message names the offending item", "[registry]") {
    CHECK_THAT(message_of("ggx(alpha=-1)"), Catch::Contains("alpha") && Catch::Contains("-1"));
    CHECK_THAT(message_of("ggx(alpha=nan)"), Catch::Contains("alpha") && Catch::Contains("nan"));
    CHECK_THAT(message_of("gtr(alpha=0.3, gamma=-1)"), Catch::Contains("gamma"));
    CHECK_THAT(message_of("gtr(alpha=1.5, gamma=2)"), Catch::Contains("alpha"));
    CHECK_THAT(message_of("phong(n=3)"), Catch::Contains("unknown ndf 'phong'"));
    CHECK_THAT(message_of("ggx(beta=1)"), Catch::Contains("unknown parameter 'beta'"));
    CHECK_THAT(message_of("gtr(alpha=0.3)"), Catch::Contains("missing parameter 'gamma'"));
    CHECK_THAT(message_of("ggx(alpha=0.3x)"), Catch::Contains("not a number"));
    CHECK_THAT(message_of("ggx(alpha=0.3"), Catch::Contains("')'"));
    CHECK_THAT(message_of("ggx(alpha=1, alpha=2)"), Catch::Contains("twice"));
    CHECK_THAT(message_of("blinn(n=-3)"), Catch::Contains("n"));
}

TEST_CASE("make(family, params) builds what the spec names, and refuses what the spec would", "[registry]") {
    const NdfRegistry r = builtin_registry();
    const AnyNdf made = r.make("gtr", {{"gamma", 1.5}, {"alpha", 0.3}}), parsed = r.make("gtr(alpha=0.3, gamma=1.5)");
    CHECK(made.spec() == "gtr(alpha=0.3, gamma=1.5)");
    for (double cos_m : {1.0, 0.9, 0.5, 0.1, 1e-3}) CHECK(made.D(cos_m) == parsed.D(cos_m));
    for (double r2 : {0.0, 0.09, 1.0, 1e6}) CHECK(made.slope_density(r2) == parsed.slope_density(r2));
    const auto message = [&](std::string_view family, const std::vector<std::pair<std::string, double>>& params) {
        try {
            r.make(family, params);
        } catch (const input_error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK_THAT(message("phong", {{"n", 3.0}}), Catch::Contains("unknown ndf 'phong'"));
    CHECK_THAT(message("bad name", {{"alpha", 0.5}}), Catch::Contains("'bad name(alpha=0.5)': expected a name"));
    CHECK_THAT(message("ggx", {{"beta", 1.0}}), Catch::Contains("unknown parameter 'beta'"));
    CHECK_THAT(message("gtr", {{"alpha", 0.3}}), Catch::Contains("missing parameter 'gamma'"));
    CHECK_THAT(message("ggx", {{"alpha", 1.0}, {"alpha", 2.0}}), Catch::Contains("'alpha' given twice"));
    CHECK_THAT(message("ggx", {{"alpha", -1.0}}), Catch::Contains("alpha") && Catch::Contains("-1"));
    CHECK_THAT(message("gtr", {{"alpha", 0.3}, {"gamma", -1.0}}), Catch::Contains("gamma"));
}

TEST_CASE("registering a user NDF is one call", "[registry]") {
    struct Flat {
        double D(double) const { return 1.0 / 3.141592653589793; }
    };
    NdfRegistry r = builtin_registry();
    r.add({"flat", {}, "uniform D", {"flat"}}, [](const NdfParams&) { return Flat{}; });
    const AnyNdf f = r.make("flat()");
    CHECK(f.spec() == "flat()");
    // Uniform D is GTR at alpha = 1, whose Lambda is 1/(2 mu (mu + sqrt(mu^2 + 1))).
    CHECK(Lambda(f, 0.5) == Approx(1.0 / (2 * 0.5 * (0.5 + std::sqrt(1.25)))).epsilon(1e-11));
    CHECK_THROWS_AS(r.add({"flat", {}, "again", {}}, [](const NdfParams&) { return Flat{}; }), input_error);
}

TEST_CASE("RFC 4180 CSV: quotes, doubled quotes, embedded newlines, CRLF, malformed rows", "[csv]") {
    std::istringstream in(
        "ndf,mu,note\r\n"
        "\"gtr(alpha=0.3, gamma=1.5)\",0.5,\"say \"\"hi\"\"\"\r\n"
        "\n"
        "\"ggx(alpha=0.1)\",2,\"two\nlines\"\n"
        "ggx(alpha=0.1),3,bad\"quote\n"
        "\"unterminated,1,x\n");
    const auto recs = read_csv(in);
    REQUIRE(recs.size() == 5);
    CHECK(recs[0].fields == std::vector<std::string>{"ndf", "mu", "note"});
    CHECK(recs[1].fields[0] == "gtr(alpha=0.3, gamma=1.5)");
    CHECK(recs[1].fields[2] == "say \"hi\"");
    CHECK(recs[2].line == 4);
    CHECK(recs[2].fields[2] == "two\nlines");
    CHECK(recs[3].line == 6);
    CHECK_FALSE(recs[3].error.empty());
    CHECK(recs[4].line == 7);
    CHECK_THAT(recs[4].error, Catch::Contains("unterminated"));
    CHECK(csv_field("a,b") == "\"a,b\"");
    CHECK(csv_field("say \"x\"") == "\"say \"\"x\"\"\"");
    CHECK(csv_field("plain") == "plain");
}
