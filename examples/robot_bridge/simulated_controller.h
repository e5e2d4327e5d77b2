// The Controller of examples/robot_bridge in simulation: the simulated H4 of
// `h4cal sim-robot` (host/campaign/simulated_controller.h: the true robot of a truth file,
// pose targets through the a priori inverse kinematics, finite joint speed, a dwell before
// "at rest"), advanced on the wall clock at each Read(). An integrator replaces this file
// with calls to their controller; nothing else in the bridge changes.
#pragma once

#include <chrono>
#include <optional>
#include <random>
#include <string>

#include "common/geometry/rigid_transform.h"
#include "examples/robot_bridge/controller.h"
#include "host/campaign/simulated_controller.h"

namespace h4::example {

class SimulatedH4Controller final : public Controller {
 public:
  /// The true robot of `truth_path` (`h4cal simulate --out-dir DIR`: DIR/truth.yaml) and
  /// the a priori robot.yaml the controller believes. Throws naming the file at fault.
  SimulatedH4Controller(const std::string& truth_path, const std::string& robot_path,
                        const host::SimulatedControllerOptions& options);
  ~SimulatedH4Controller() override;

  bool MoveToPose(const EePoseTarget& x_B, std::string* why) override;
  bool MoveToJoints(const JointPositions& q, std::string* why) override;
  JointReading Read() override;

  /// Simulation only: the true board pose X_CT that `h4cam run --source sim` renders.
  RigidTransform true_X_CT() const;

 private:
  void AdvanceToNow();

  std::unique_ptr<host::SimulatedController> robot_;
  std::mt19937_64 rng_{1};
  std::optional<std::chrono::steady_clock::time_point> last_step_;
  int64_t next_id_ = 0;  ///< the simulation wants an id per target; the bridge keeps its own
};

}  // namespace h4::example
