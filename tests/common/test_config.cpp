// Config reader: defaults, overrides, and the rejection of unknown keys, wrong
// types and out-of-range values with the key, the value and the expectation named.
#include "common/config.hpp"
#include "common/error.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

namespace {

using aniso::InputError;
using aniso::config::Range;
using aniso::config::Reader;
using ::testing::AllOf;
using ::testing::HasSubstr;

toml::table parse(const char* text) {
  return toml::parse(text);
}

template <class Body> std::string error_of(Body body) {
  try {
    body();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return {};
}

TEST(Config, DefaultsAndFileValues) {
  Reader reader(parse("[dem]\nfriction = 0.4\ncount = 12\n"), "'test.toml'");
  EXPECT_EQ(reader.real("dem.friction", 0.5, "1", Range::non_negative(), "mu"), 0.4);
  EXPECT_EQ(reader.real("dem.density", 2650.0, "kg/m^3", Range::positive(), "rho"), 2650.0);
  EXPECT_EQ(reader.integer("dem.count", 1000, Range::closed(2, 1e9), "n"), 12);
  EXPECT_NO_THROW(reader.reject_unknown());
}

TEST(Config, IntegerAcceptedWhereRealExpected) {
  Reader reader(parse("[dem]\npressure = 100000\n"), "x");
  EXPECT_EQ(reader.real("dem.pressure", 1.0, "Pa", Range::positive(), "p"), 1e5);
}

TEST(Config, UnknownKeyNamed) {
  Reader reader(parse("[dem]\nfriction = 0.4\nfrictoin = 0.3\n"), "'a.toml'");
  reader.real("dem.friction", 0.5, "1", Range::non_negative(), "mu");
  const std::string message = error_of([&] { reader.reject_unknown(); });
  EXPECT_THAT(message,
              AllOf(HasSubstr("unknown config key"), HasSubstr("'dem.frictoin'"), HasSubstr("a.toml")));
}

TEST(Config, ForeignSectionsTolerated) {
  Reader reader(parse("[lbm]\ntau = 0.8\n[dem]\nx = 1\n"), "x");
  reader.tolerate_sections({"lbm"});
  EXPECT_THAT(error_of([&] { reader.reject_unknown(); }), HasSubstr("'dem.x'"));
}

TEST(Config, WrongTypeNamesKeyValueAndExpectation) {
  Reader reader(parse("[dem]\nfriction = \"high\"\n"), "'b.toml'");
  const std::string message =
      error_of([&] { reader.real("dem.friction", 0.5, "1", Range::non_negative(), "mu"); });
  EXPECT_THAT(message,
              AllOf(HasSubstr("'dem.friction'"), HasSubstr("high"), HasSubstr("expected a real number")));
  Reader integer_reader(parse("n = 1.5\n"), "x");
  EXPECT_THAT(error_of([&] { integer_reader.integer("n", 1, Range::positive(), "count"); }),
              AllOf(HasSubstr("'n'"), HasSubstr("1.5"), HasSubstr("expected an integer")));
  Reader bool_reader(parse("flag = 1\n"), "x");
  EXPECT_THAT(error_of([&] { bool_reader.boolean("flag", false, "f"); }),
              HasSubstr("expected true or false"));
}

TEST(Config, OutOfRangeNamesKeyValueAndRange) {
  Reader reader(parse("[dem]\npoisson_ratio = 0.7\n"), "'c.toml'");
  const std::string message =
      error_of([&] { reader.real("dem.poisson_ratio", 0.15, "1", Range::open(-1.0, 0.5), "nu"); });
  EXPECT_THAT(message, AllOf(HasSubstr("'dem.poisson_ratio'"), HasSubstr("0.7"), HasSubstr("(-1, 0.5)")));
  Reader list_reader(parse("strains = [0.1, -0.2]\n"), "x");
  EXPECT_THAT(error_of([&] { list_reader.reals("strains", {}, "1", Range::positive(), 1, "s"); }),
              AllOf(HasSubstr("element 1"), HasSubstr("-0.2")));
}

TEST(Config, InfiniteValuesAreOutOfEveryRange) {
  // +inf passed every (0, inf) range: a density or a stress of inf made runs that never end.
  Reader reader(parse("[dem]\ndensity = inf\nfriction = -inf\nstrains = [0.1, inf]\n"), "'d.toml'");
  EXPECT_THAT(error_of([&] { reader.real("dem.density", 2650.0, "kg/m^3", Range::positive(), "rho"); }),
              AllOf(HasSubstr("'dem.density'"), HasSubstr("inf"), HasSubstr("out of range")));
  EXPECT_THAT(error_of([&] { reader.real("dem.friction", 0.5, "1", Range{}, "mu"); }),
              HasSubstr("'dem.friction'"));
  EXPECT_THAT(error_of([&] { reader.reals("dem.strains", {}, "1", Range::positive(), 1, "s"); }),
              AllOf(HasSubstr("element 1"), HasSubstr("inf")));
  EXPECT_FALSE(Range::non_negative().contains(std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(Range::non_negative().contains(1e300));
}

TEST(Config, QuotedDottedKeyIsRefused) {
  // "dem.seed" = 7 is one key named dem.seed at the top level: it matched the spelling of the
  // known key in the unknown-key check and was never read.
  Reader top(parse("\"dem.seed\" = 7\n"), "'e.toml'");
  EXPECT_THAT(error_of([&] { top.reject_unknown(); }),
              AllOf(HasSubstr("\"dem.seed\""), HasSubstr("e.toml"), HasSubstr("must not contain a dot")));
  Reader nested(parse("[dem]\n\"load.final_strain\" = 0.1\n"), "x");
  EXPECT_THAT(error_of([&] { nested.reject_unknown(); }),
              AllOf(HasSubstr("\"load.final_strain\""), HasSubstr("[dem]")));
}

TEST(Config, ChoiceRejectsUnlistedWord) {
  Reader reader(parse("mode = \"mrt\"\n"), "x");
  EXPECT_THAT(error_of([&] {
                reader.choice("mode", "trt", {"trt", "bgk"}, "collision");
              }),
              AllOf(HasSubstr("\"mrt\""), HasSubstr("trt | bgk")));
}

TEST(Config, OverridesParseTomlValuesAndCreateTables) {
  toml::table table = parse("[dem]\nfriction = 0.5\n");
  aniso::config::apply_override(table, "dem.friction=0.25");
  aniso::config::apply_override(table, "dem.particles.count=64");
  aniso::config::apply_override(table, "dem.output_dir=runs/a");
  aniso::config::apply_override(table, "dem.strains=[0.1, 0.2]");
  Reader reader(table, "x");
  EXPECT_EQ(reader.real("dem.friction", 0.5, "1", Range::non_negative(), "mu"), 0.25);
  EXPECT_EQ(reader.integer("dem.particles.count", 1, Range::positive(), "n"), 64);
  EXPECT_EQ(reader.text("dem.output_dir", ".", "dir"), "runs/a");
  EXPECT_EQ(reader.reals("dem.strains", {}, "1", Range::positive(), 2, "s").size(), 2u);
  EXPECT_THAT(error_of([&] { aniso::config::apply_override(table, "no-equals-sign"); }),
              HasSubstr("key=value"));
  EXPECT_THAT(error_of([&] { aniso::config::apply_override(table, "dem.friction.x=1"); }),
              HasSubstr("not a table"));
}

TEST(Config, EffectiveTomlIsValidTomlWithDefaults) {
  Reader reader(parse(""), "defaults");
  reader.real("dem.material.friction", 0.5, "1", Range::non_negative(), "mu");
  reader.integer("dem.seed", 1, Range::non_negative(), "seed");
  reader.text("dem.output_dir", ".", "dir");
  const std::string printed = reader.effective_toml();
  const toml::table reparsed = toml::parse(printed);
  EXPECT_EQ(reparsed.at_path("dem.material.friction").value<double>(), 0.5);
  EXPECT_EQ(reparsed.at_path("dem.seed").value<std::int64_t>(), 1);
  EXPECT_THAT(printed, HasSubstr("allowed: [0, inf)"));
}

TEST(Config, SyntaxErrorNamesFileAndLine) {
  const std::string path = "config_syntax_error.toml";
  std::ofstream(path) << "[dem]\nfriction = = 0.5\n";
  EXPECT_THAT(error_of([&] { aniso::config::load_file(path); }), AllOf(HasSubstr(path), HasSubstr("line 2")));
  EXPECT_THROW(aniso::config::load_file("does-not-exist.toml"), aniso::FileError);
}

} // namespace
