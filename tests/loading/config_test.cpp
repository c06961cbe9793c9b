// The run configuration alone: defaults, units as written, overrides, and rejected input.
#include "loading/config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace rupture::loading {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_config(text, "test.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Config, DefaultsAndDemParametersInInternalUnits) {
  const RunConfig c = parse_config("[sample]\nlattice = \"chain\"\n[bonds]\nstiffness = 2e3\n", "test.toml");
  EXPECT_FALSE(c.dt.has_value()) << "dt defaults to auto";
  EXPECT_EQ(c.speed, 50.0);
  const dem::Params p = c.dem_params(2.5e-4);
  EXPECT_EQ(p.bond_stiffness, 2e3);
  EXPECT_EQ(p.contact_stiffness, 2e3) << "contacts as stiff as bonds by default";
  EXPECT_EQ(p.glue_stiffness, 2e4) << "glue ten times stiffer";
  EXPECT_EQ(p.density, 2.5e-4) << "the sample's density unless overridden";
  EXPECT_EQ(p.break_rule, dem::BreakRule::absolute);
}

TEST(Config, OverridesAcceptTomlValuesAndBareWords) {
  const RunConfig c =
      parse_config("[sample]\nlattice = \"chain\"\n", "test.toml",
                   {"time.dt=1e-8", "bonds.break_rule=relative", "sample.lattice_cells=[2, 5, 3]"});
  ASSERT_TRUE(c.dt.has_value());
  EXPECT_EQ(*c.dt, 1e-8);
  EXPECT_EQ(c.break_rule, "relative");
  EXPECT_EQ(c.lattice_cells[2], 3);
  const RunConfig automatic =
      parse_config("[sample]\nlattice = \"chain\"\n[time]\ndt = 1e-8\n", "t", {"time.dt=auto"});
  EXPECT_FALSE(automatic.dt.has_value());
}

// k_n is ESyS's normalK (N/mm^2) with scale_stiffness, b_d a strain under the relative rule.
TEST(Config, BondUnitsFollowTheStiffnessScalingAndTheBreakRule) {
  const RunConfig plain = parse_config("[sample]\nlattice = \"chain\"\n", "test.toml");
  EXPECT_EQ(bond_stiffness_unit(plain), "N/mm");
  EXPECT_EQ(break_distance_unit(plain), "mm");
  const RunConfig esys = parse_config("[sample]\nlattice = \"chain\"\n", "test.toml",
                                      {"bonds.scale_stiffness=true", "bonds.break_rule=relative"});
  EXPECT_EQ(bond_stiffness_unit(esys), "N/mm^2");
  EXPECT_EQ(break_distance_unit(esys), "1");
}

TEST(Config, ResolvedJsonHasEveryKey) {
  const auto json = to_json(parse_config("[sample]\npreset = \"tissue\"\n", "test.toml"));
  EXPECT_EQ(json["bonds"]["stiffness"], 1e3);
  EXPECT_EQ(json["time"]["dt"], "auto");
  EXPECT_EQ(json["sample"]["density"], nullptr);
  EXPECT_EQ(json["monitor"]["window"], 41);
  EXPECT_EQ(json.size(), 11u) << json.dump();
}

TEST(Config, BadInputIsRejectedWithFileKeyAndFix) {
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n[bond]\nstiffness = 1\n"),
              HasSubstr("test.toml: bond.stiffness: unknown key"));
  EXPECT_THAT(error_of("stiffness = 1\n"), HasSubstr("every key belongs to a [section]"));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n[bonds]\nstiffness = \"stiff\"\n"),
              HasSubstr("expects a number"));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n[bonds]\nbreak_rule = \"esys\"\n"),
              HasSubstr("use one of \"absolute\", \"relative\""));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\npreset = \"tissue\"\n"),
              HasSubstr("more than one sample given"));
  // A value given by --set is reported as the --set, not as the file's.
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n", {"loading.speed=-1"}),
              HasSubstr("--set loading.speed: -1 is outside the plausible range [1e-09, 1e+09] mm/s"));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n", {"bonds.stiffness=abc"}),
              StartsWith("--set bonds.stiffness: expects a number"));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n[loading]\nspeed = -1\n", {"bonds.stiffness=5"}),
              HasSubstr("test.toml: loading.speed: -1 is outside the plausible range"));
  EXPECT_THAT(error_of("[sample]\nlattice = \"chain\"\n", {"time.dtt=1"}),
              HasSubstr("--set time.dtt: unknown key"));
  EXPECT_THAT(error_of("[sample\n"), HasSubstr("test.toml:1"));
}

}  // namespace
}  // namespace rupture::loading
