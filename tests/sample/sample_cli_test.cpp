// `rupture sample` end to end: generate, info --json, convert, errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sample/formats.hpp"
#include "sample/stats.hpp"
#include "support/json_convention.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::run_rupture;

TEST(SampleCli, GenerateThenInfoJsonReportsTheSampleStatistics) {
  const testing::TempDir dir;
  const auto file = (dir / "t.sample").string();
  const auto gen = run_rupture("sample generate --preset tissue-small --seed 3 --out '" + file + "'");
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_THAT(gen.out, HasSubstr("solid fraction"));
  const auto info = run_rupture("sample info --json '" + file + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto doc = nlohmann::json::parse(info.out);
  EXPECT_THAT(testing::json_convention_breaches(doc), ::testing::IsEmpty());
  EXPECT_EQ(doc.at("radius").at("mean").at("unit"), "mm");
  const SampleStats stats = compute_stats(load_sample(file));
  EXPECT_EQ(doc.at("particles").get<std::size_t>(), stats.particles);
  EXPECT_EQ(doc.at("bonds").get<std::size_t>(), stats.bonds);
  EXPECT_DOUBLE_EQ(doc.at("solid_fraction").get<double>(), stats.solid_fraction);
  EXPECT_DOUBLE_EQ(doc.at("mean_coordination").get<double>(), stats.mean_coordination);
  EXPECT_THAT(doc.at("version").get<std::string>(), HasSubstr("0."));
  EXPECT_EQ(doc.at("inputs").at("file").get<std::string>(), file);
}

TEST(SampleCli, SameSeedSameFileAndConvertRoundTrips) {
  const testing::TempDir dir;
  const auto a = (dir / "a.sample").string(), b = (dir / "b.sample").string();
  ASSERT_EQ(run_rupture("sample generate --preset tissue-small --seed 11 --out '" + a + "'").exit_code, 0);
  ASSERT_EQ(run_rupture("sample generate --preset tissue-small --seed 11 --out '" + b + "'").exit_code, 0);
  EXPECT_EQ(testing::slurp(a), testing::slurp(b));
  const auto data = (dir / "a.data").string(), geo = (dir / "a.geo").string(),
             back = (dir / "back.sample").string();
  ASSERT_EQ(run_rupture("sample convert '" + a + "' '" + data + "'").exit_code, 0);
  ASSERT_EQ(run_rupture("sample convert '" + data + "' '" + geo + "'").exit_code, 0);
  ASSERT_EQ(run_rupture("sample convert '" + geo + "' '" + back + "'").exit_code, 0);
  EXPECT_EQ(format_own(load_sample(a)).substr(format_own(load_sample(a)).find("\nbox ")),
            format_own(load_sample(back)).substr(format_own(load_sample(back)).find("\nbox ")));
}

TEST(SampleCli, OptionsOverrideThePresetAndFormatCanBeForced) {
  const testing::TempDir dir;
  const auto out = (dir / "x.txt").string();
  const auto r = run_rupture(
      "sample generate --preset tissue-small --width 8 --height 6 --depth 3 --seed 1 --format lsm --out '" +
      out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Sample s = load_sample(out);
  EXPECT_EQ(s.box.size(), (Vec3{8.0, 6.0, 3.0}));
  EXPECT_THAT(testing::slurp(out), ::testing::StartsWith("LSMGeometry 1.2"));
}

TEST(SampleCli, BadInputExitsWithCodeTwoAndTheFix) {
  const testing::TempDir dir;
  const auto r = run_rupture("sample generate --preset tissue-large --seed 1 --out '" +
                             (dir / "x.sample").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("use one of: tissue, tissue-small"));
  const auto bad = dir / "bad.sample";
  {
    std::FILE* f = std::fopen(bad.c_str(), "w");
    std::fputs("rupture-sample 1\nbox 0 0 0 1 1 1\ndensity 1\nparticles 3\n0 0 0 0 0.1 free\n", f);
    std::fclose(f);
  }
  const auto info = run_rupture("sample info '" + bad.string() + "'");
  EXPECT_EQ(info.exit_code, 2);
  EXPECT_THAT(info.err, HasSubstr("bad.sample:5: file ends where particle 2 of 3 was expected"));
}

}  // namespace
}  // namespace rupture
