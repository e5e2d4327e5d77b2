// The folder `h4cal simulate --out-dir DIR` writes and `h4cal validate --sim-dir DIR` reads
// (README.md's walkthrough puts identify's results there too): one place that names its
// files, so that the writer and the readers cannot drift apart.
#pragma once

#include <filesystem>
#include <string>

#include <fmt/core.h>

#include "host/kinematics/model_kind.h"

namespace h4::host {

struct SimulationFolder {
  std::filesystem::path dir;

  std::string dataset() const { return File("dataset.csv"); }
  std::string apriori_robot() const { return File("robot.yaml"); }
  std::string truth() const { return File("truth.yaml"); }
  /// The held-out poses' true joints and true board poses: `h4cal fk --joints
  /// heldout_joints.csv --compare heldout_truth.csv` scores an identification.
  std::string heldout_joints() const { return File("heldout_joints.csv"); }
  std::string heldout_truth() const { return File("heldout_truth.csv"); }
  /// With `simulate --board`: the corners the poses were solved from.
  std::string corners() const { return File("corners.csv"); }
  /// The ruler runs of the straightness experiment (paper IV.D), k = 1, 2.
  std::string straightness(int k) const { return File(fmt::format("straightness_{}.csv", k)); }
  /// Where the walkthrough's `identify --out` puts each model's result.
  std::string result(ModelKind model) const {
    return File(std::string("result") + ToString(model) + ".json");
  }

 private:
  std::string File(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace h4::host
