#include "common/robot/parameter_names.h"

#include <gtest/gtest.h>

namespace h4 {
namespace {

TEST(ParameterNames, LengthsOfBothModelsArePositiveLengths) {
  for (const char* name : {"h", "arm", "forearm", "R", "arm3", "forearm4"}) {
    EXPECT_TRUE(IsPositiveLengthParameter(name)) << name;
  }
  // Positions may be zero or negative: base joint positions, the offset d, frame translations.
  for (const char* name : {"d", "x2", "z4", "X_BC.tx", "alpha1"}) {
    EXPECT_FALSE(IsPositiveLengthParameter(name)) << name;
  }
}

TEST(ParameterNames, ModelAnglesAndFrameRotationsAreAngles) {
  for (const char* name : {"alpha", "alpha2", "q0", "q03", "psi1", "beta4"}) {
    EXPECT_TRUE(IsModelAngleParameter(name)) << name;
    EXPECT_TRUE(IsAngleParameter(name)) << name;
  }
  for (const char* name : {"X_BC.rx", "X_TE.rz"}) {
    EXPECT_FALSE(IsModelAngleParameter(name)) << name;
    EXPECT_TRUE(IsAngleParameter(name)) << name;
  }
  for (const char* name : {"X_BC.tx", "X_TE.tz", "h", "R", "d", "y3"}) {
    EXPECT_FALSE(IsAngleParameter(name)) << name;
  }
}

}  // namespace
}  // namespace h4
