#include <gtest/gtest.h>

#include "pbms/error.hpp"
#include "pbms/units.hpp"

using pbms::units::Dimension;
using pbms::units::parse_quantity;

TEST(Units, PlainNumbersAreCanonical) {
  EXPECT_DOUBLE_EQ(parse_quantity("298", Dimension::kTemperature), 298.0);
  EXPECT_DOUBLE_EQ(parse_quantity(" 1e4 ", Dimension::kPressure), 1.0e4);
}

TEST(Units, ConvertsToMetal) {
  EXPECT_DOUBLE_EQ(parse_quantity("5 GPa", Dimension::kPressure), 5.0e4);
  EXPECT_DOUBLE_EQ(parse_quantity("2fs", Dimension::kTime), 0.002);
  EXPECT_DOUBLE_EQ(parse_quantity("3846 m/s", Dimension::kVelocity), 38.46);
  EXPECT_DOUBLE_EQ(parse_quantity("0.1 %/ps", Dimension::kRate), 0.001);
  EXPECT_DOUBLE_EQ(parse_quantity("1 nm", Dimension::kLength), 10.0);
  // 1 J/m^2 = 1 J / 1e20 Å^2 = 6.241509e18 eV / 1e20 Å^2 (the SI's exact eV;
  // metal units keep CODATA 2014's, 8e-9 away).
  EXPECT_NEAR(parse_quantity("1 J/m^2", Dimension::kSurfaceEnergy), 6.241509074e-2, 1e-9);
  EXPECT_NEAR(parse_quantity("1345 mJ/m^2", Dimension::kSurfaceEnergy), 1.345 * 6.241509074e-2,
              1e-9);
  EXPECT_NEAR(pbms::units::to_metal(1.0, "J/m^2"), 6.241509074e-2, 1e-9);
}

TEST(Units, RejectsWrongDimensionAndGarbage) {
  EXPECT_THROW(parse_quantity("5 ps", Dimension::kPressure), pbms::Error);
  EXPECT_THROW(parse_quantity("GPa", Dimension::kPressure), pbms::Error);
  EXPECT_THROW(parse_quantity("2 K", Dimension::kNone), pbms::Error);
  try {
    parse_quantity("5 furlongs", Dimension::kLength);
    FAIL();
  } catch (const pbms::Error& e) {
    EXPECT_NE(std::string(e.what()).find("accepted units are"), std::string::npos);
  }
}
