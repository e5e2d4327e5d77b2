// Robot description YAML: common/formats/README.md's example, the optional blocks, exact round
// trip, and every kind of malformed value with its line and field.
#include "host/formats/robot_yaml.h"

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

// common/formats/README.md's example, line for line (line 1 is the comment).
const std::string kExample =
    R"(# a priori description of the H4 and of the measurement set-up (SI units)
model12:
  h: 0.06
  arm: 0.26
  forearm: 0.48
  R: 0.14
  d: 0.0
  alpha: [0, 3.1416, 4.7124, 4.7124]
  q0: [0, 0, 0, 0]
assembly:
  bar: [1, -1, 1, -1]        # s_i
  elbow: [-1, -1, -1, -1]    # eps_i
X_BC:                        # a priori camera pose in base
  translation: [0, 0, -1.05]
  rpy: [0, 0, 0]
X_TE:                        # a priori end-effector pose in board frame
  translation: [0.09, 0.09, 0.025]
  rpy: [0, 0, 0]
)";

// The example with line `line` (1-based) replaced.
std::string Replace(int line, const std::string& text) {
  std::string out;
  size_t start = 0;
  for (int n = 1; start < kExample.size(); ++n) {
    const size_t end = kExample.find('\n', start);
    out += (n == line ? text : kExample.substr(start, end - start)) + "\n";
    start = end + 1;
  }
  return out;
}

// FailsWith for `text` read as "r.yaml".
::testing::AssertionResult YamlFails(const std::string& text, int line, const std::string& field,
                                     const std::string& expected) {
  return FailsWith([&] { ParseRobotYaml(text, "r.yaml"); }, "r.yaml", line, field, expected);
}

// The example with line `line` replaced by `text` fails on that line, naming `field`.
::testing::AssertionResult ExampleLineFails(int line, const std::string& text,
                                            const std::string& field, const std::string& expected) {
  return YamlFails(Replace(line, text), line, field, expected);
}

const std::string kModel31 = R"(model31:
  x2: 0.28
  y2: 0.001
  z2: -0.002
  x3: 0.14
  y3: 0.14
  z3: 0
  x4: 0.14
  y4: 0.14
  z4: 0.003
  psi: [0, 3.14, 4.71, 4.71]
  beta: [-1.5708, -1.57, -1.571, -1.5707]
  q0: [0.01, 0, 0, -0.01]
  arm: [0.26, 0.261, 0.259, 0.26]
  forearm: [0.48, 0.48, 0.481, 0.479]
  h: 0.061
  d: 0.001
)";

TEST(RobotYaml, ReadsTheExampleOfFormatsMd) {
  const RobotDescription robot = ParseRobotYaml(kExample, "robot.yaml");
  EXPECT_EQ(robot.model12.h, 0.06);
  EXPECT_EQ(robot.model12.arm, 0.26);
  EXPECT_EQ(robot.model12.forearm, 0.48);
  EXPECT_EQ(robot.model12.R, 0.14);
  EXPECT_EQ(robot.model12.d, 0.0);
  EXPECT_EQ(robot.model12.alpha, (std::array<double, 4>{0, 3.1416, 4.7124, 4.7124}));
  EXPECT_EQ(robot.model12.q0, (std::array<double, 4>{0, 0, 0, 0}));
  EXPECT_EQ(robot.assembly.bar, (std::array<int, 4>{1, -1, 1, -1}));
  EXPECT_EQ(robot.assembly.elbow, (std::array<int, 4>{-1, -1, -1, -1}));
  EXPECT_EQ(robot.X_BC.translation(), Eigen::Vector3d(0, 0, -1.05));
  EXPECT_EQ(robot.X_BC.rotation(), Eigen::Matrix3d::Identity());
  EXPECT_EQ(robot.X_TE.translation(), Eigen::Vector3d(0.09, 0.09, 0.025));
  EXPECT_FALSE(robot.model31.has_value());
}

// The template the workstation package installs (examples/robot.yaml, share/h4cal/examples)
// reads as the paper's a priori robot, the values it says it holds.
TEST(RobotYaml, TheInstalledTemplateIsThePapersAprioriRobot) {
  const RobotDescription robot =
      ReadRobotYaml(std::string(H4_SOURCE_DIR) + "/examples/robot.yaml");
  const RobotDescription paper = ParseRobotYaml(kExample, "robot.yaml");
  EXPECT_EQ(robot.model12.h, paper.model12.h);
  EXPECT_EQ(robot.model12.arm, paper.model12.arm);
  EXPECT_EQ(robot.model12.forearm, paper.model12.forearm);
  EXPECT_EQ(robot.model12.R, paper.model12.R);
  EXPECT_EQ(robot.model12.d, paper.model12.d);
  EXPECT_EQ(robot.model12.alpha, paper.model12.alpha);
  EXPECT_EQ(robot.model12.q0, paper.model12.q0);
  EXPECT_EQ(robot.assembly.bar, paper.assembly.bar);
  EXPECT_EQ(robot.assembly.elbow, paper.assembly.elbow);
  EXPECT_TRUE(robot.X_BC.IsNearlyEqualTo(paper.X_BC, 0.0, 0.0));
  EXPECT_TRUE(robot.X_TE.IsNearlyEqualTo(paper.X_TE, 0.0, 0.0));
}

TEST(RobotYaml, AssemblyIsOptionalAndExtraTopLevelKeysAreIgnored) {
  std::string text = kExample;
  const size_t a = text.find("assembly:");
  text.erase(a, text.find("X_BC:") - a);
  text += "comment: robot of the lab\nserial: 12\n";
  const RobotDescription robot = ParseRobotYaml(text, "robot.yaml");
  EXPECT_EQ(robot.assembly.bar, Assembly{}.bar);
  EXPECT_EQ(robot.assembly.elbow, Assembly{}.elbow);
  // A partial assembly block keeps the default for what it omits.
  const RobotDescription partial = ParseRobotYaml(Replace(12, "  # no elbow"), "robot.yaml");
  EXPECT_EQ(partial.assembly.elbow, Assembly{}.elbow);
}

TEST(RobotYaml, ReadsTheModel31Block) {
  const RobotDescription robot = ParseRobotYaml(kExample + kModel31, "robot.yaml");
  ASSERT_TRUE(robot.model31.has_value());
  const Model31Parameters& m = *robot.model31;
  EXPECT_EQ(m.P[0], Eigen::Vector3d(0.28, 0.001, -0.002));
  EXPECT_EQ(m.P[1], Eigen::Vector3d(0.14, 0.14, 0));
  EXPECT_EQ(m.P[2], Eigen::Vector3d(0.14, 0.14, 0.003));
  EXPECT_EQ(m.psi[1], 3.14);
  EXPECT_EQ(m.beta[3], -1.5707);
  EXPECT_EQ(m.q0[3], -0.01);
  EXPECT_EQ(m.arm[1], 0.261);
  EXPECT_EQ(m.forearm[3], 0.479);
  EXPECT_EQ(m.h, 0.061);
  EXPECT_EQ(m.d, 0.001);
}

TEST(RobotYaml, RoundTripIsExact) {
  RobotDescription robot = ParseRobotYaml(kExample + kModel31, "robot.yaml");
  robot.model12.h = 1.0 / 3 * 0.18;
  robot.model12.alpha = {-0.0015, 3.1016, 4.6807, 4.6859};
  robot.assembly.elbow = {1, -1, 1, -1};
  robot.X_BC = RigidTransform::FromTranslationRpy({0.001, -0.002, -1.05}, {0.01, -0.02, 3.0});
  const RobotDescription back = ParseRobotYaml(FormatRobotYaml(robot), "mem");
  EXPECT_EQ(back.model12.h, robot.model12.h);
  EXPECT_EQ(back.model12.alpha, robot.model12.alpha);
  EXPECT_EQ(back.assembly.bar, robot.assembly.bar);
  EXPECT_EQ(back.assembly.elbow, robot.assembly.elbow);
  EXPECT_EQ(back.X_BC.translation(), robot.X_BC.translation());
  // The rotation travels as roll-pitch-yaw: a few ulp.
  EXPECT_LT((back.X_BC.rotation() - robot.X_BC.rotation()).cwiseAbs().maxCoeff(), 1e-15);
  ASSERT_TRUE(back.model31.has_value());
  EXPECT_EQ(back.model31->P[2], robot.model31->P[2]);
  EXPECT_EQ(back.model31->beta, robot.model31->beta);
  EXPECT_EQ(back.model31->forearm, robot.model31->forearm);
  EXPECT_EQ(back.model31->d, robot.model31->d);
  // Through a file, without model31.
  robot.model31.reset();
  const std::string path = TempPath("robot.yaml");
  WriteRobotYaml(path, robot);
  const RobotDescription from_file = ReadRobotYaml(path);
  EXPECT_FALSE(from_file.model31.has_value());
  EXPECT_EQ(from_file.model12.q0, robot.model12.q0);
}

TEST(RobotYaml, WriterStartsWithAComment) {
  EXPECT_EQ(FormatRobotYaml(RobotDescription{}).rfind("# ", 0), 0u);
}

TEST(RobotYamlErrors, MissingKeyNamesTheBlockLine) {
  EXPECT_TRUE(YamlFails(Replace(5, "  # no forearm"), 2, "model12.forearm", "missing key"));
  // A missing top-level block is on no line.
  std::string text = kExample;
  text.erase(text.find("X_TE:"));
  EXPECT_TRUE(YamlFails(text, 0, "X_TE", "missing"));
}

TEST(RobotYamlErrors, UnknownKeyInABlockIsAnError) {
  // A misspelt key is never matched to the intended one, nor ignored in favour of a default.
  EXPECT_TRUE(ExampleLineFails(5, "  forarm: 0.48", "model12.forarm",
                               "unknown key, expected one of: h, arm, forearm"));
  EXPECT_TRUE(ExampleLineFails(12, "  elbows: [1, 1, 1, 1]", "assembly.elbows", "unknown key"));
  EXPECT_TRUE(ExampleLineFails(15, "  RPY: [0, 0, 0]", "X_BC.RPY", "unknown key"));
  EXPECT_TRUE(
      YamlFails(kExample + "Model31:\n  h: 1\n", 19, "Model31", "case-sensitive: 'model31'"));
}

TEST(RobotYamlErrors, NonNumber) {
  EXPECT_TRUE(ExampleLineFails(4, "  arm: 0.26m", "model12.arm", "expected a number, got '0.26m'"));
  EXPECT_TRUE(ExampleLineFails(7, "  d: .nan", "model12.d", "expected a number"));
  EXPECT_TRUE(ExampleLineFails(3, "  h:", "model12.h", "got nothing"));
  EXPECT_TRUE(
      ExampleLineFails(8, "  alpha: [0, pi, 4.7124, 4.7124]", "model12.alpha[1]", "got 'pi'"));
}

TEST(RobotYamlErrors, WrongListLength) {
  EXPECT_TRUE(
      ExampleLineFails(9, "  q0: [0, 0, 0]", "model12.q0", "list of 4 numbers, got a list of 3"));
  EXPECT_TRUE(ExampleLineFails(14, "  translation: 0", "X_BC.translation", "list of 3"));
}

TEST(RobotYamlErrors, NonPositiveLength) {
  EXPECT_TRUE(ExampleLineFails(6, "  R: -0.14", "model12.R", "positive"));
  EXPECT_TRUE(ExampleLineFails(3, "  h: 0", "model12.h", "positive"));
  std::string text = kExample + kModel31;
  text.replace(text.find("arm: [0.26, 0.261"), 17, "arm: [0.26, -0.26");
  // model31 starts on line 19; arm is its 13th key.
  EXPECT_TRUE(YamlFails(text, 32, "model31.arm[1]", "positive"));
}

// issue 27 points 2 and 5: nothing bounded robot.yaml's numbers; h = 1e154 made `identify`
// loop, X_TE.translation x = -1e308 made `analyze` print NaN. Lengths and positions are
// bounded at 10 m like the result JSON's, angles at a turn, each error with line and field.
TEST(RobotYamlErrors, ValuesBeyondAnyRobotNameTheField) {
  EXPECT_TRUE(ExampleLineFails(3, "  h: 1e154", "model12.h", "within 10 m, got 1e+154"));
  EXPECT_TRUE(ExampleLineFails(5, "  forearm: 10.01", "model12.forearm", "within 10 m"));
  EXPECT_TRUE(ExampleLineFails(7, "  d: -1e308", "model12.d", "within 10 m"));
  EXPECT_TRUE(ExampleLineFails(8, "  alpha: [0, 3.1416, 4.7124, 1e300]", "model12.alpha[3]",
                               "within one turn"));
  EXPECT_TRUE(ExampleLineFails(14, "  translation: [0, 1e154, -1.05]", "X_BC.translation[1]",
                               "within 10 m"));
  EXPECT_TRUE(ExampleLineFails(17, "  translation: [-1e308, 0.09, 0.025]", "X_TE.translation[0]",
                               "within 10 m"));
  EXPECT_TRUE(ExampleLineFails(18, "  rpy: [0, 7, 0]", "X_TE.rpy[1]", "within one turn"));
  std::string text = kExample + kModel31;
  text.replace(text.find("arm: [0.26, 0.261"), 17, "arm: [0.26, 1e200");
  EXPECT_TRUE(YamlFails(text, 32, "model31.arm[1]", "within 10 m"));
  EXPECT_NO_THROW(ParseRobotYaml(Replace(5, "  forearm: 10"), "r.yaml"));
}

TEST(RobotYamlErrors, AssemblySignMustBePlusOrMinusOne) {
  EXPECT_TRUE(
      ExampleLineFails(11, "  bar: [1, -1, 2, -1]", "assembly.bar[2]", "expected 1 or -1, got 2"));
  EXPECT_TRUE(ExampleLineFails(12, "  elbow: [-1, -1, -1, -1.0]", "assembly.elbow[3]",
                               "expected an integer"));
}

TEST(RobotYamlErrors, IncompleteModel31Block) {
  std::string text = kExample + kModel31;
  text.erase(text.find("  y3: 0.14\n"), 11);
  EXPECT_TRUE(YamlFails(text, 19, "model31.y3", "missing key"));
}

TEST(RobotYamlErrors, DuplicateKeyAndBadSyntax) {
  EXPECT_TRUE(ExampleLineFails(7, "  h: 0.07", "model12.h", "key given twice (first on line 3)"));
  EXPECT_TRUE(YamlFails(Replace(8, "  alpha: [0, 3.1416"), 9, "", "invalid YAML"));
  EXPECT_TRUE(YamlFails("", 0, "", "mapping"));
  EXPECT_TRUE(YamlFails("# robot\nmodel12: [1, 2]\n", 2, "model12",
                        "expected a mapping of keys to values, got a list"));
}

// yaml-cpp recurses once per nesting level without a limit: a file nested 100,000 deep
// overflowed the stack. The depth is checked before parsing, naming the line.
TEST(RobotYamlErrors, DeepNestingIsRefusedBeforeParsing) {
  const std::string flow = kExample + "extra: " + std::string(100000, '[') + "\n";
  EXPECT_TRUE(YamlFails(flow, 19, "", "flow collections nested deeper than the limit"));
  std::string compact = kExample + "extra:\n";
  for (int i = 0; i < 100000; ++i) compact += "- ";
  compact += "x\n";
  EXPECT_TRUE(YamlFails(compact, 20, "", "block collections nested deeper"));
  const std::string indented = kExample + "extra:\n" + std::string(300, ' ') + "a: 1\n";
  EXPECT_TRUE(YamlFails(indented, 20, "", "a line indented"));
  // Brackets in quotes and comments, and an apostrophe, are not nesting.
  const std::string text = kExample + "note: don't [ stop\nother: \"" + std::string(100, '[') +
                           "\"  # " + std::string(100, '{') + "\n";
  EXPECT_NO_THROW(ParseRobotYaml(text, "r.yaml"));
  // ... and a bracket in a plain scalar does not switch the block checks off.
  std::string after_bracket = kExample + "note: a [\nextra:\n";
  for (int i = 0; i < 100000; ++i) after_bracket += "- ";
  EXPECT_TRUE(YamlFails(after_bracket + "x\n", 21, "", "block collections nested deeper"));
}

}  // namespace
}  // namespace h4
