#include "io/quantity.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/json_convention.hpp"

namespace rupture::io {
namespace {

TEST(Quantity, WritesValueErrorAndUnitAndReadsTheValueBack) {
  const auto q = quantity(0.25, 0.01, "%");
  EXPECT_EQ(q.dump(), R"({"error":0.01,"unit":"%","value":0.25})");
  EXPECT_EQ(quantity_value(q), 0.25);
  EXPECT_EQ(quantity_value(nlohmann::json::parse(q.dump())), 0.25) << "through text";
  EXPECT_EQ(quantity({0.1, 0.2}, "mm")["value"].size(), 2u);
}

TEST(Quantity, UndefinedValuesAreNullAndReadAsMissing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(quantity(nan, "s")["value"].is_null());
  EXPECT_TRUE(quantity({1.0, INFINITY}, "s")["value"][1].is_null());
  EXPECT_TRUE(quantity(std::optional<double>(), "s").is_null());
  EXPECT_EQ(quantity_value(quantity(nan, "s")), std::nullopt);
  EXPECT_EQ(quantity_value(nullptr), std::nullopt);
  EXPECT_EQ(quantity_value("text"), std::nullopt);
}

// Files of builds before the convention wrote bare numbers; readers that must take them get them.
TEST(Quantity, ABareNumberReadsAsItsValue) { EXPECT_EQ(quantity_value(7.0), 7.0); }

TEST(Quantity, UnitOfAQuotient) {
  EXPECT_EQ(unit_ratio("mJ", "%"), "mJ/%");
  EXPECT_EQ(unit_ratio("mJ", "1"), "mJ");
  EXPECT_EQ(unit_ratio("N", "mJ/%"), "N/(mJ/%)");
}

// The checker the output tests use finds each kind of breach (so that its silence means something).
TEST(JsonConvention, CheckerFindsUnitsInKeysUnitsObjectsAndUnitsWithoutValues) {
  using ::testing::IsEmpty;
  using ::testing::SizeIs;
  EXPECT_THAT(testing::json_convention_breaches({{"wall_time", quantity(1.0, "s")}, {"steps", 3}}),
              IsEmpty());
  EXPECT_THAT(testing::json_convention_breaches({{"wall_s", 1.0}}), SizeIs(1));
  EXPECT_THAT(testing::json_convention_breaches({{"plan", {{"plate_work_mJ", 1.0}}}}), SizeIs(1));
  EXPECT_THAT(testing::json_convention_breaches({{"units", {{"strain", "%"}}}}), SizeIs(1));
  EXPECT_THAT(testing::json_convention_breaches({{"window", {1, 2}}, {"window_unit", "%"}}), SizeIs(1));
  EXPECT_THAT(testing::json_convention_breaches({{"x", {{"unit", "%"}}}}), SizeIs(1));
  EXPECT_THAT(testing::json_convention_breaches(nlohmann::json::array({{{"dt_s", 1e-7}}})), SizeIs(1));
}

}  // namespace
}  // namespace rupture::io
