// `h4cal collect` as a user runs it (the program, files, exit codes) against hostile input
// on the live path: a recorded log holding messages that do not decode (string
// lengths 0 and negative, joint_count -1, random bytes after a valid fingerprint) is read to
// the end by --from-log, and a second campaign on a dataset another one is writing is
// refused without touching the file. Skipped when the program is not built.
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <h4msgs/board_pose_t.hpp>
#include <h4msgs/camera_status_t.hpp>
#include <h4msgs/joint_state_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include "host/formats/dataset_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/paper_robot.h"
#include "messages/channels.h"
#include "tests/support/test_dir.h"

extern char** environ;

namespace h4::host {
namespace {

namespace fs = std::filesystem;

const std::string kH4cal = H4_BINARY_DIR "/host/h4cal";

std::string LogOrDatasetText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `args` through the shell with stdout and stderr into `output`; the exit code.
int RunProgram(const std::string& args, std::string* output) {
  const std::string log = fs::temp_directory_path() / fmt::format("h4_collect_{}", getpid());
  const int status = std::system((args + " > " + log + " 2>&1").c_str());
  *output = LogOrDatasetText(log);
  fs::remove(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

class LogWriter {
 public:
  explicit LogWriter(const std::string& path) : log_(path, "w") {}
  bool good() const { return log_.good(); }

  template <class Msg>
  void Write(const char* channel, const Msg& msg) {
    std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    WriteRaw(channel, bytes);
  }
  void WriteRaw(const char* channel, std::vector<uint8_t> bytes) {
    lcm::LogEvent event{};
    event.eventnum = next_++;
    event.timestamp = utime_;
    event.channel = channel;
    event.datalen = static_cast<int32_t>(bytes.size());
    event.data = bytes.data();
    log_.writeEvent(&event);
    utime_ += 1000;
  }
  int64_t utime() const { return utime_; }

 private:
  lcm::LogFile log_;
  int64_t next_ = 0;
  int64_t utime_ = 1'700'000'000'000'000;
};

void PutBigEndian32(std::vector<uint8_t>* bytes, size_t pos, int32_t value) {
  const auto u = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) (*bytes)[pos + static_cast<size_t>(i)] = uint8_t(u >> (24 - 8 * i));
}

template <class Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

h4msgs::joint_state_t SettledAt(int64_t pose_id, int64_t utime) {
  h4msgs::joint_state_t js{};
  js.utime = utime;
  js.pose_id = pose_id;
  js.joint_count = 4;
  js.position = {0.01 * static_cast<double>(pose_id), 0.2, 0.3,
                 0.4};  // within a turn (the reader's bound)
  js.settled = true;
  return js;
}

h4msgs::board_pose_t MeasurementOf(int64_t pose_id, int64_t utime) {
  h4msgs::board_pose_t m{};
  m.utime = utime;
  m.pose_id = pose_id;
  m.camera_id = "sim";
  m.board_id = "board";
  m.translation[2] = 0.5 + 0.01 * static_cast<double>(pose_id);
  m.quaternion[0] = 1.0;
  for (int i = 0; i < 6; ++i) m.covariance[i * 7] = 1e-8;
  m.status = h4msgs::board_pose_t::STATUS_OK;
  return m;
}

/// The hostile messages, then each pose's settled readings and measurement.
int WriteHostileCampaignLog(const std::string& path, int poses) {
  LogWriter log(path);
  EXPECT_TRUE(log.good());
  int hostile = 0;
  std::mt19937 rng(13);
  for (int64_t id = 1; id <= poses; ++id) {
    for (int32_t length : {0, -1, INT_MIN}) {
      std::vector<uint8_t> pose = Encode(MeasurementOf(id, log.utime()));
      PutBigEndian32(&pose, 8 + 16, length);  // camera_id's length
      log.WriteRaw(channels::kBoardPose, pose);
      h4msgs::camera_status_t status{};
      status.camera_id = "sim";
      std::vector<uint8_t> bytes = Encode(status);
      PutBigEndian32(&bytes, 8 + 8, length);  // camera_id's length
      log.WriteRaw(channels::kCameraStatus, bytes);
      hostile += 2;
    }
    std::vector<uint8_t> joints = Encode(SettledAt(id, log.utime()));
    PutBigEndian32(&joints, 8 + 16, -1);  // joint_count
    log.WriteRaw(channels::kJointState, joints);
    std::vector<uint8_t> noise(8 + rng() % 400);
    for (uint8_t& b : noise) b = static_cast<uint8_t>(rng());
    const auto hash = static_cast<uint64_t>(h4msgs::board_pose_t::getHash());
    for (int k = 0; k < 8; ++k) noise[static_cast<size_t>(k)] = uint8_t(hash >> (56 - 8 * k));
    log.WriteRaw(channels::kBoardPose, noise);
    hostile += 2;
    for (int k = 0; k < 5; ++k) log.Write(channels::kJointState, SettledAt(id, log.utime()));
    log.Write(channels::kBoardPose, MeasurementOf(id, log.utime() - 2000));
  }
  return hostile;
}

void WritePlan(const std::string& path, int poses) {
  std::ofstream plan(path);
  plan << "pose_id,X,Y,Z,theta\n";
  for (int id = 1; id <= poses; ++id) plan << id << "," << 0.01 * id << ",0,-0.45,0\n";
}

class CollectCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kH4cal)) GTEST_SKIP() << kH4cal << " not built";
    dir_ = FreshTestDir("h4_collect_cmd_");
    plan_ = (dir_ / "plan.csv").string();
    log_ = (dir_ / "campaign.lcmlog").string();
    out_ = (dir_ / "dataset.csv").string();
    WritePlan(plan_, 3);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  std::string Collect(const std::string& args) const {
    return kH4cal + " collect --out " + out_ + " --plan " + plan_ + " " + args;
  }
  fs::path dir_;
  std::string plan_, log_, out_;
};

TEST_F(CollectCommandTest, FromLogReadsPastMessagesThatDoNotDecode) {
  const int hostile = WriteHostileCampaignLog(log_, 3);
  std::string output;
  const int code = RunProgram(Collect("--from-log " + log_), &output);
  EXPECT_EQ(code, 0) << output;
  const std::vector<DatasetRow> rows = ReadDatasetCsv(out_);
  ASSERT_EQ(rows.size(), 3u) << output;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(rows[static_cast<size_t>(i)].pose_id, i + 1);
  EXPECT_NE(output.find(fmt::format("{} undecodable", hostile)), std::string::npos) << output;
}

// Issue 42, defect 4: joint states beyond one turn (7 rad, 1e300 rad) were recorded and the
// dataset's own reader then refused it whole. They are refused where they enter, counted
// as impossible, and the poses measured only with them are skipped: the dataset reads back.
TEST_F(CollectCommandTest, JointReadingsBeyondTheReadersBoundAreNeverWritten) {
  {
    LogWriter log(log_);
    ASSERT_TRUE(log.good());
    for (int64_t id = 1; id <= 3; ++id) {
      h4msgs::joint_state_t joints = SettledAt(id, log.utime());
      if (id == 2) joints.position[1] = 7.0;
      if (id == 3) joints.position[3] = -1e300;
      for (int k = 0; k < 5; ++k) {
        joints.utime = log.utime();
        log.Write(channels::kJointState, joints);
      }
      log.Write(channels::kBoardPose, MeasurementOf(id, log.utime() - 2000));
    }
  }
  std::string output;
  EXPECT_EQ(RunProgram(Collect("--from-log " + log_), &output), 3) << output;
  const std::vector<DatasetRow> rows = ReadDatasetCsv(out_);
  ASSERT_EQ(rows.size(), 1u) << output;
  EXPECT_EQ(rows[0].pose_id, 1);
  EXPECT_NE(output.find("10 impossible"), std::string::npos) << output;
  EXPECT_NE(output.find("beyond one turn"), std::string::npos) << output;
}

// Issue 42, defect 10: a new campaign beside an old STEM.corners.csv kept the old corners
// for its poses, exit 0. It is refused, naming the corners file, and the file is untouched.
TEST_F(CollectCommandTest, ANewCampaignBesideAnotherCampaignsCornersIsRefused) {
  WriteHostileCampaignLog(log_, 3);
  const std::string corners = (dir_ / "dataset.corners.csv").string();
  const std::string old_corners =
      "pose_id,tag_id,corner,u,v,sigma_px\n1,0,0,100,200,0.1\n2,0,0,110,200,0.1\n";
  std::ofstream(corners) << old_corners;
  std::string output;
  EXPECT_EQ(RunProgram(Collect("--from-log " + log_), &output), 1) << output;
  EXPECT_NE(output.find(corners + ": holds the corners of 2 poses"), std::string::npos) << output;
  EXPECT_EQ(LogOrDatasetText(corners), old_corners);
  EXPECT_TRUE(ReadDatasetCsv(out_).empty());
}

// Issue 42, defect 11: `--sequential 3,4` measured 4 poses and printed "predicted inf mm"
// and "chi-square / dof -441", exit 0; `20,20000` failed only after the first stage. The
// counts are checked before anything is planned, written or moved.
TEST_F(CollectCommandTest, SequentialCountsAreCheckedBeforeAnythingMoves) {
  const std::string robot = (dir_ / "robot.yaml").string();
  WriteRobotYaml(robot, PaperAprioriRobot());
  const std::string sequential = kH4cal + " collect --out " + out_ + " --robot " + robot +
                                 " --camera " H4_SOURCE_DIR
                                 "/boards/sim_camera_1024x768.yaml --board " H4_SOURCE_DIR
                                 "/boards/aprilgrid_6x6_30mm.yaml --lcm-url memq:// --sequential ";
  for (const char* counts : {"3,4", "0,10", "5,6", "8,7", "1,1000000", "20,20000"}) {
    std::string output;
    EXPECT_EQ(RunProgram(sequential + counts, &output), 1) << counts << ": " << output;
    EXPECT_NE(output.find("--sequential FIRST,TOTAL"), std::string::npos) << output;
    EXPECT_EQ(output.find("stage 1 of 2"), std::string::npos) << counts << ": " << output;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_TRUE(entry.path().filename() == "robot.yaml" || entry.path().filename() == "plan.csv")
          << counts << ": wrote " << entry.path();
    }
  }
}

// Issue 44: a sequential campaign is planned for the measurement `plan` is told of. The
// noise options need --sequential, and a corner sigma outside the corners CSV's bounds
// stops the campaign before stage 1 is planned, written or moved.
TEST_F(CollectCommandTest, SequentialTakesThePlannersNoiseOptions) {
  const std::string robot = (dir_ / "robot.yaml").string();
  WriteRobotYaml(robot, PaperAprioriRobot());
  std::string output;
  EXPECT_GE(RunProgram(kH4cal + " collect --out " + out_ + " --corner-sigma-px 0.4", &output),
            100)
      << output;
  EXPECT_NE(output.find("--corner-sigma-px requires --sequential"), std::string::npos) << output;
  const std::string sequential = kH4cal + " collect --out " + out_ + " --robot " + robot +
                                 " --camera " H4_SOURCE_DIR
                                 "/boards/sim_camera_1024x768.yaml --board " H4_SOURCE_DIR
                                 "/boards/aprilgrid_6x6_30mm.yaml --lcm-url memq:// "
                                 "--sequential 20,40 --setup-sigma-mm 10 --setup-sigma-deg 1 "
                                 "--corner-sigma-px 500";
  EXPECT_EQ(RunProgram(sequential, &output), 1) << output;
  EXPECT_NE(output.find("--corner-sigma-px: "), std::string::npos) << output;
  EXPECT_EQ(output.find("stage 1 of 2:"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(out_)) << "nothing is written before the plan";
}

// Issue 42, defect 5: a resumed sequential campaign whose stage-2 plan file was empty or
// reused stage 1's pose ids measured nothing of stage 2 and exited 0 ("6 of 6 planned
// poses"). Stage 1 is whole in the dataset here, so nothing waits on the bus.
TEST_F(CollectCommandTest, AResumedSecondStageThatIsNotTheRestIsRefusedNamingIt) {
  const std::string robot = (dir_ / "robot.yaml").string();
  WriteRobotYaml(robot, PaperAprioriRobot());
  const std::string first = (dir_ / "dataset.stage1.plan.csv").string();
  const std::string second = (dir_ / "dataset.stage2.plan.csv").string();
  WritePlan(first, 6);
  std::vector<DatasetRow> rows;
  for (int64_t id = 1; id <= 6; ++id) {
    DatasetRow row;
    row.pose_id = id;
    row.utime = 1'700'000'000'000'000 + id;
    row.q = {0.01 * static_cast<double>(id), 0.2, 0.3, 0.4};
    row.X_CT =
        RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.0, 0.0, 0.5), Eigen::Vector3d::Zero());
    row.sigma_t = 2e-4;
    row.sigma_r = 5e-4;
    rows.push_back(row);
  }
  WriteDatasetCsv(out_, rows);
  const std::string sequential =
      kH4cal + " collect --out " + out_ + " --robot " + robot +
      " --camera " H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml --board " H4_SOURCE_DIR
      "/boards/aprilgrid_6x6_30mm.yaml --lcm-url memq:// --sequential 6,9";
  struct Case {
    std::string plan, expected;
  };
  for (const Case& c : {Case{"pose_id,X,Y,Z,theta\n", "holds no pose"},
                        Case{"pose_id,X,Y,Z,theta\n1,0.01,0,-0.45,0\n2,0.02,0,-0.45,0\n"
                             "7,0.07,0,-0.45,0\n",
                             "reuses pose ids of the first stage (1, 2)"},
                        Case{"pose_id,X,Y,Z,theta\n7,0.07,0,-0.45,0\n", "holds 1 poses"}}) {
    std::ofstream(second) << c.plan;
    std::string output;
    EXPECT_EQ(RunProgram(sequential, &output), 1) << output;
    EXPECT_NE(output.find(second), std::string::npos) << output;
    EXPECT_NE(output.find(c.expected), std::string::npos) << output;
    EXPECT_EQ(ReadDatasetCsv(out_).size(), 6u);
  }
}

/// True once another process holds the lock on `path` (polled; gives up after 20 s).
bool WaitUntilLockedByAnother(const std::string& path) {
  for (int i = 0; i < 2000; ++i) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
      const bool taken = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
      ::close(fd);  // releases the lock if this probe took it
      if (taken) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST_F(CollectCommandTest, ASecondCampaignOnTheSameDatasetIsRefusedAndTheFileStaysIntact) {
  WriteHostileCampaignLog(log_, 2);  // poses 1 and 2: the first campaign resumes at 3
  std::string output;
  ASSERT_EQ(RunProgram(Collect("--from-log " + log_), &output), 3) << output;

  // The first campaign listens (passive, udpm in a private network namespace: the
  // namespace script execs, so the pid stays the program's) until interrupted.
  const std::string netns = H4_SOURCE_DIR "/scripts/in-private-netns";
  const int check = std::system((netns + " --check > /dev/null 2>&1").c_str());
  if (WIFEXITED(check) && WEXITSTATUS(check) == 77) {
    GTEST_SKIP() << "no private network namespace here (" << netns << " --check)";
  }
  const std::string first_log = (dir_ / "first.log").string();
  const std::vector<std::string> args = {
      netns,    kH4cal, "collect",   "--out",     out_,
      "--plan", plan_,  "--passive", "--lcm-url", "udpm://239.255.76.67:7667?ttl=0"};
  std::vector<char*> argv;
  std::vector<std::string> copies = args;
  for (auto& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, first_log.c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_adddup2(&actions, 2, 1);
  pid_t first = 0;
  ASSERT_EQ(posix_spawn(&first, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const bool locked = WaitUntilLockedByAnother(out_);
  const std::string before = LogOrDatasetText(out_);

  const int second = RunProgram(Collect("--from-log " + log_), &output);
  ::kill(first, SIGINT);
  int status = 0;
  ::waitpid(first, &status, 0);

  ASSERT_TRUE(locked) << "the first campaign never locked " << out_ << ": "
                      << LogOrDatasetText(first_log);
  EXPECT_EQ(second, 1) << output;
  EXPECT_NE(output.find(fmt::format("another campaign is writing it (process {}", first)),
            std::string::npos)
      << output;
  EXPECT_EQ(LogOrDatasetText(out_), before);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << LogOrDatasetText(first_log);
  EXPECT_EQ(ReadDatasetCsv(out_).size(), 2u);
}

// `collect --from-log` killed (SIGKILL) at random points, 20 times, each run resuming the
// last, then run to the end: the dataset is byte for byte the one an uninterrupted run
// writes (every row once, none lost; a row cut by a kill is dropped and written again).
TEST_F(CollectCommandTest, KilledAtRandomPointsAndResumedWritesTheSameDatasetAsOneRun) {
  constexpr int kPoses = 150;
  WritePlan(plan_, kPoses);
  WriteHostileCampaignLog(log_, kPoses);
  std::string output;
  const std::string reference = (dir_ / "reference.csv").string();
  ASSERT_EQ(RunProgram(
                kH4cal + " collect --out " + reference + " --plan " + plan_ + " --from-log " + log_,
                &output),
            0)
      << output;

  std::mt19937 rng(11);
  int killed = 0;
  for (int run = 0; run < 20; ++run) {
    std::vector<std::string> args = {kH4cal,   "collect", "--out",      out_,
                                     "--plan", plan_,     "--from-log", log_};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    std::this_thread::sleep_for(std::chrono::microseconds(rng() % 60000));
    if (::kill(pid, SIGKILL) == 0) ++killed;
    int status = 0;
    ::waitpid(pid, &status, 0);
  }
  ASSERT_EQ(RunProgram(Collect("--from-log " + log_), &output), 0) << output;
  EXPECT_EQ(LogOrDatasetText(out_), LogOrDatasetText(reference));
  EXPECT_GT(killed, 0) << "no run was killed: nothing was tested";
}

// Issue 26: the plan is checked against the a priori robot before the robot moves. --dry-run
// names each pose out of reach by id, X, Y, Z and theta, touches neither the bus nor the
// dataset, and exits 3; a plan within reach passes with 0.
TEST_F(CollectCommandTest, DryRunNamesThePosesTheAprioriRobotCannotTake) {
  const std::string robot = (dir_ / "robot.yaml").string();
  WriteRobotYaml(robot, PaperAprioriRobot());
  std::string output;
  EXPECT_EQ(RunProgram(Collect("--robot " + robot + " --dry-run"), &output), 0) << output;
  EXPECT_NE(output.find("0 of 3 planned poses out of the a priori robot's reach"),
            std::string::npos)
      << output;
  {
    std::ofstream plan(plan_, std::ios::app);
    plan << "4,0.0,0.0,-1.5,0\n";  // a metre below the workspace
  }
  EXPECT_EQ(RunProgram(Collect("--robot " + robot + " --dry-run"), &output), 3) << output;
  EXPECT_NE(output.find("1 of 4 planned poses out of the a priori robot's reach"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("pose 4 (X 0.0, Y 0.0, Z -1500.0 mm, theta 0.0 deg): legs 1, 2, 3, 4 "
                        "out of reach"),
            std::string::npos)
      << output;
  EXPECT_FALSE(fs::exists(out_)) << "a dry run writes nothing";
  // A joint range the plan's joints leave: named by joint.
  EXPECT_EQ(RunProgram(Collect("--robot " + robot + " --dry-run --joint-range-deg 0,1"), &output),
            3)
      << output;
  EXPECT_NE(output.find("outside the joint range 0.0..1.0 deg"), std::string::npos) << output;
  EXPECT_NE(RunProgram(Collect("--dry-run"), &output), 0) << "--dry-run needs --robot";
}

}  // namespace
}  // namespace h4::host
