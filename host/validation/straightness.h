// Straightness validation (paper IV.D, Table 4): the end-effector slides along a straight
// ruler while the joints are logged; forward kinematics with some parameters turns the
// readings into positions, and the RMS distance of those positions to their least-squares
// line measures how straight the model believes the motion was. Also the simulated run: the
// true robot's joints along a straight line, with encoder noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/formats/joints_csv.h"
#include "host/kinematics/kinematic_model.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

/// Least-squares 3D line (the principal axis of the points).
struct LineFit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       ///< centroid, m
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit
  std::vector<double> distances;                         ///< per point, distance to the line, m
  double rms_distance = 0.0;                             ///< m
  double max_distance = 0.0;                             ///< m
  double length = 0.0;                                   ///< extent of the points along the line, m
};

/// Needs at least 3 points spread over more than 1 mm; returns false otherwise.
bool FitLine(const std::vector<Eigen::Vector3d>& points, LineFit* fit);

struct StraightnessRun {
  bool ok = false;
  std::string message;                     ///< why not ok
  std::vector<int64_t> pose_ids;           ///< readings used, in order
  std::vector<Eigen::Vector3d> positions;  ///< FK positions in the model's base, m
  std::vector<int64_t> failed;             ///< readings where FK failed
  LineFit fit;
};

/// Forward kinematics of each reading (each started from the previous pose) and the line
/// fit. Not ok when fewer than 3 readings give a pose or the fit fails.
StraightnessRun StraightnessOf(const KinematicModel& model, const std::vector<JointsRow>& joints);

/// A straight ruler in B for the simulation: `count` poses from start to end (theta fixed).
struct RulerLine {
  EePose start = EePose(-0.08, 0.0, -0.45, 0.0);
  EePose end = EePose(0.08, 0.0, -0.45, 0.0);
  int count = 33;
};

/// The true robot's encoder readings along the line (true IK plus seeded Gaussian noise of
/// sigma_q rad), pose ids 1..count. Throws std::invalid_argument when a pose is out of reach.
std::vector<JointsRow> SimulateRulerRun(const SimulatedRobot& robot, const RulerLine& line,
                                        double sigma_q, uint64_t seed);

/// The paper's two ruler directions: 1 along x_B, 2 along the diagonal x_B + y_B, both
/// 160 mm long through the workspace centre (0, 0, -0.45) m at theta = 0.
std::vector<RulerLine> PaperRulerLines();

}  // namespace h4::host
