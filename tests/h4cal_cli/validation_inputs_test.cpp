// Tests of validate's inputs and console text (host/cli/validation_inputs.h): what the
// console says of held-out and in-sample poses and of measured squares, and how
// --square-measured is split.
#include "host/cli/validation_inputs.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "host/validation/validation.h"
#include "tests/support/text_checks.h"
#include "tests/validation/validation_test_helpers.h"

namespace h4::host {
namespace {

// validate's console with every pose in the fit: the Table 3 and positioning figures are
// in-sample and say so; the held-out accuracy is the cross-validated RMS; no "held out".
TEST(ValidateText, EveryPoseInTheFitIsInSampleBesideTheCrossValidatedRms) {
  const std::string text = cli::FormatValidationText(Validate(EveryPoseInTheFit()));
  EXPECT_TRUE(Contains(text,
                       "Table 3: joint residuals, in-sample (81 poses, none held out of the "
                       "fit) (deg, measured - model)"));
  EXPECT_TRUE(Contains(text,
                       "  Model 12   in-sample (81 poses, none held out of the fit): 0.0000 "
                       "mm, 0.0000 deg\n"));
  EXPECT_TRUE(Contains(text,
                       "  Model 12   10-fold cross-validated (held-out) RMS over 81 poses: "
                       "1.8734 mm, 0.1203 deg\n"));
  EXPECT_FALSE(Contains(text, "held out:"));
  EXPECT_FALSE(Contains(text, "held-out poses"));
  EXPECT_FALSE(Contains(text, "(mean)")) << "accuracy in RMS";
}

TEST(ValidateText, HeldOutPosesAreCountedAsNotInTheFit) {
  const std::string text = cli::FormatValidationText(Validate(PaperValidationInputs()));
  EXPECT_TRUE(Contains(text, "Table 3: joint residuals, held out (10 poses not in the fit)"));
  EXPECT_TRUE(
      Contains(text, "  Model 12   held out (10 poses not in the fit): 0.0000 mm, 0.0000 deg\n"));
  EXPECT_FALSE(Contains(text, "in-sample"));
}

TEST(ValidateText, MeasuredSquaresArePrinted) {
  const std::string text =
      cli::FormatValidationText(Validate(WithMeasuredSquares(PaperValidationInputs())));
  EXPECT_TRUE(Contains(text, "Square (measured), a priori controller, in Model 12's base frame: "
                             "shape "));
  EXPECT_TRUE(Contains(text,
                       "Square (measured), Model 12 controller, in Model 12's base frame (its "
                       "own): shape 0.00 mm (offset removed); side RMS 0.00 0.00 0.00 0.00 mm"));
  EXPECT_TRUE(Contains(text, "  offset: mean measured - commanded position."));
}

// A label names the model that drove the run (its square is judged in that model's frame);
// any other controller is nullopt.
TEST(ValidationInputs, SquareMeasuredLabelNamesTheModelThatDroveTheRun) {
  EXPECT_EQ(cli::ModelDrivingSquare("Model 12"), ModelKind::k12);
  EXPECT_EQ(cli::ModelDrivingSquare("Model 31"), ModelKind::k31);
  EXPECT_EQ(cli::ModelDrivingSquare("model31"), ModelKind::k31);
  EXPECT_EQ(cli::ModelDrivingSquare("31"), ModelKind::k31);
  EXPECT_EQ(cli::ModelDrivingSquare("a priori"), std::nullopt);
  EXPECT_EQ(cli::ModelDrivingSquare("Model 13"), std::nullopt);
  EXPECT_EQ(cli::ModelDrivingSquare("Model 12 retake"), std::nullopt);
}

TEST(ValidationInputs, SquareMeasuredSplitsLabelAndDatasetAtTheFirstEquals) {
  const auto [label, path] = cli::SplitSquareMeasured("Model 12=runs/a=b.csv");
  EXPECT_EQ(label, "Model 12");
  EXPECT_EQ(path, "runs/a=b.csv");
  EXPECT_THROW(cli::SplitSquareMeasured("sq.csv"), std::invalid_argument);
  EXPECT_THROW(cli::SplitSquareMeasured("=sq.csv"), std::invalid_argument);
  EXPECT_THROW(cli::SplitSquareMeasured("a priori="), std::invalid_argument);
}

}  // namespace
}  // namespace h4::host
