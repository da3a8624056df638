// Persistence of the object memory (issue 23, items 2, 3, 5 and the kill -9 loop): the real recognition
// node, started and killed by this test against a real roscore. Every object whose learn call was
// acknowledged must be there after a kill -9 at a random moment; killed saves leave no temporaries
// behind once the node has started again; a refused memory is kept aside, never overwritten; a damaged
// descriptor model stops the node with a message naming the file and the problem.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include <biovision_msgs/LearnObject.h>
#include <biovision_msgs/ListObjects.h>
#include <biovision_ros_common/async_service_client.hpp>
#include <biovision_ros_common/rostest_helpers.hpp>
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>

#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/object_memory.hpp"

namespace fs = std::filesystem;

namespace
{
std::string shared(const std::string& name)
{
  const char* env = std::getenv("BIOVISION_SHARED");
  return std::string(env ? env : BIOVISION_DEFAULT_SHARED) + "/" + name;
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// Files in `dir` whose name starts with `prefix`.
std::vector<std::string> filesStartingWith(const std::string& dir, const std::string& prefix)
{
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(prefix, 0) == 0)
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// A service call that gives up after `timeout` wall seconds (false), through AsyncServiceClient: roscpp's
/// own call has no time-out, and in one CI run (2026-12-06) this test hung for good in its 11th kill
/// round, most likely in a call racing a kill -9.
template <class Service>
bool callWithin(const std::string& name, Service& srv, double timeout = 10.0)
{
  biovision_ros_common::AsyncServiceClient<Service> client(ros::NodeHandle(), name, timeout);
  if (!client.start(srv.request))
    return false;
  for (;;)
  {
    if (auto result = client.take())
    {
      if (result->answered)
        srv.response = result->response;
      return result->answered;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

/// The recognition node in its own process, its output in a log file.
class NodeProcess
{
public:
  NodeProcess(const std::vector<std::string>& params, const std::string& log) : log_(log)
  {
    // BIOVISION_NODE_UNDER_TEST runs another build's node (e.g. main's, to see these tests fail there).
    const char* other = std::getenv("BIOVISION_NODE_UNDER_TEST");
    std::vector<std::string> args{other ? other : BIOVISION_RECOGNITION_NODE, "__name:=recognition",
                                  "image:=camera/image", "_lazy:=false"};
    args.insert(args.end(), params.begin(), params.end());
    pid_ = biovision_ros_common::spawnProcess(args, "", log);
  }
  ~NodeProcess()
  {
    if (running())
      kill(SIGKILL);
  }
  pid_t pid() const { return pid_; }
  bool running()
  {
    if (exited_)
      return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_)
    {
      exited_ = true;
      status_ = status;
    }
    return !exited_;
  }
  void kill(int signal)
  {
    ::kill(pid_, signal);
    wait(10.0);
  }
  /// Waits for the process to end; its wait status, or -1 after `seconds`.
  int wait(double seconds)
  {
    for (int i = 0; i < seconds * 20 && running(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return exited_ ? status_ : -1;
  }
  std::string log() const { return readFile(log_); }

private:
  std::string log_;
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = 0;
};

class Persistence : public testing::Test
{
protected:
  void SetUp() override
  {
    dir_ = (fs::temp_directory_path() / ("biovision_persistence_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    memory_file_ = dir_ + "/objects.bin";
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 2);
    diagnostics_sub_ = nh_.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 20, [this](const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& s : m->status)
            if (s.name.find("Recognition") != std::string::npos)
              for (const auto& kv : s.values)
                diagnostics_[kv.key] = kv.value;
        });
    // A COIL object in a textured scene, published all the time: every restarted node gets images.
    cv::Mat scene(240, 320, CV_8UC3);
    cv::randu(scene, cv::Scalar::all(90), cv::Scalar::all(150));
    cv::GaussianBlur(scene, scene, cv::Size(), 5.0);
    const cv::Mat object = cv::imread(shared("data/objects/coil100/obj1__0.png"), cv::IMREAD_COLOR);
    ASSERT_FALSE(object.empty());
    object.copyTo(scene(cv::Rect(40, 60, object.cols, object.rows)));
    image_ = cv_bridge::CvImage(std_msgs::Header(), "bgr8", scene).toImageMsg();
    spinner_.start();
    publisher_ = std::thread([this] {
      while (!stop_)
      {
        image_->header.stamp = ros::Time::now();
        image_pub_.publish(image_);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    });
  }
  void TearDown() override
  {
    // The spinner outlives every member (declared first): stop the callbacks before mutex_ and diagnostics_ go.
    diagnostics_sub_.shutdown();
    spinner_.stop();
    stop_ = true;
    if (publisher_.joinable())  // SetUp may have failed before starting it
      publisher_.join();
    fs::remove_all(dir_);
  }

  /// Starts the node with this memory file; returns it once its services answer (or fails the test).
  std::unique_ptr<NodeProcess> start(const std::string& log_name, std::vector<std::string> params = {})
  {
    params.push_back("_memory_file:=" + memory_file_);
    auto node = std::make_unique<NodeProcess>(params, dir_ + "/" + log_name);
    for (int i = 0; i < 300 && node->running(); ++i)
    {
      biovision_msgs::ListObjects list;
      if (ros::service::exists("recognition/list_objects", false) && callWithin("recognition/list_objects", list))
        return node;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ADD_FAILURE() << "the node did not start; its log:\n" << node->log();
    return nullptr;
  }

  static biovision_msgs::LearnObject learnRequest(const std::string& label)
  {
    biovision_msgs::LearnObject learn;
    learn.request.label = label;
    learn.request.box.x_offset = 40;
    learn.request.box.y_offset = 60;
    learn.request.box.width = 128;
    learn.request.box.height = 128;
    return learn;
  }

  /// Learns `label`, retrying while the node has no image yet; true once acknowledged.
  static bool learn(const std::string& label)
  {
    for (int i = 0; i < 100; ++i)
    {
      auto req = learnRequest(label);
      if (callWithin("recognition/learn_object", req) && req.response.success)
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  static std::set<std::string> listed()
  {
    biovision_msgs::ListObjects list;
    EXPECT_TRUE(callWithin("recognition/list_objects", list));
    return {list.response.labels.begin(), list.response.labels.end()};
  }

  std::string diagnostic(const std::string& key, double timeout)
  {
    for (int i = 0; i < timeout * 20; ++i)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = diagnostics_.find(key);
        if (it != diagnostics_.end())
          return it->second;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return "";
  }

  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher image_pub_;
  ros::Subscriber diagnostics_sub_;
  sensor_msgs::ImagePtr image_;
  std::thread publisher_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::map<std::string, std::string> diagnostics_;
  std::string dir_, memory_file_;
};
}  // namespace

// kill -9 at random moments while objects are learned (each learn saves the memory file): nothing
// acknowledged is lost, the node starts every time, and no temporary stays once it has started.
TEST_F(Persistence, KillDuringSavesLosesNothingAcknowledgedAndLeavesNoDebris)
{
  // A memory of some size (about 11 MB: 600 views of 500 keypoints, 60 objects), so that a save takes a
  // while, as on a robot that has learned for some time.
  {
    const auto model = biovision_recognition::DescriptorModel::load(std::string(BIOVISION_RECOGNITION_MODELS) + "/" +
                                                                    biovision_recognition::kDefaultModelFile);
    biovision_recognition::ObjectMemory memory(model.bits(), model.id());
    std::mt19937_64 bits(5);
    for (int v = 0; v < 600; ++v)
    {
      biovision_recognition::ObjectView view;
      view.label = "seed_" + std::to_string(v / 10);
      view.size = {128, 128};
      view.codes = biovision_recognition::BinaryCodeSet(model.bits(), 500);
      for (int k = 0; k < 500; ++k)
      {
        view.keypoints.push_back({float(k % 128), float(k / 4), 5.66f, 1.f, 0.5f});
        for (int w = 0; w < view.codes.words(); ++w)
          view.codes.code(k)[w] = bits();
      }
      memory.addView(std::move(view));
    }
    memory.save(memory_file_);
  }
  const size_t seeded = 60;
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> delay_ms(150, 1200);
  std::set<std::string> acknowledged;
  int kills = 0, temporaries_left = 0, planted = 0, counter = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(35);
  while (kills < 20 && std::chrono::steady_clock::now() < deadline)
  {
    auto node = start("kill_" + std::to_string(kills) + ".log");
    ASSERT_TRUE(node) << "start " << kills;
    const auto present = listed();
    EXPECT_GE(present.size(), seeded + acknowledged.size());
    for (const auto& label : acknowledged)
      ASSERT_TRUE(present.count(label)) << "'" << label << "' was acknowledged but is gone after kill " << kills;
    EXPECT_TRUE(present.count("seed_0") && present.count("seed_59")) << "the seeded objects are gone";
    EXPECT_TRUE(filesStartingWith(dir_, "objects.bin.tmp.").empty())
        << "temporaries of killed saves remain after start " << kills;
    // Learn in a loop and kill -9: in even rounds at a random moment; in odd rounds, once a learn of the
    // round is acknowledged, the moment the next save's temporary appears (in the middle of writing it).
    std::atomic<bool> killed{false};
    std::atomic<int> round_acks{0};
    std::mutex ack_mutex;
    std::thread learner([&] {
      while (!killed)
      {
        const std::string label = "object_" + std::to_string(counter++);
        auto req = learnRequest(label);
        if (callWithin("recognition/learn_object", req) && req.response.success)
        {
          std::lock_guard<std::mutex> lock(ack_mutex);
          acknowledged.insert(label);
          ++round_acks;
        }
      }
    });
    // A save's temporary is objects.bin.tmp.<pid>.<n> (writeFileAtomically).
    const std::string debris_prefix = "objects.bin.tmp." + std::to_string(node->pid()) + ".";
    const auto debris_left = [&] { return !filesStartingWith(dir_, debris_prefix).empty(); };
    if (kills % 2 == 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    else
    {
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(4);
      while (std::chrono::steady_clock::now() < until && (round_acks == 0 || !debris_left()))
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    node->kill(SIGKILL);
    killed = true;
    learner.join();
    ++kills;
    if (debris_left())
      ++temporaries_left;
    else
    {
      // This kill missed the save: leave what a kill inside it leaves, so every restart is tested on debris.
      writeFile(dir_ + "/" + debris_prefix + "0", std::string(4096, 'x'));
      ++planted;
    }
  }
  auto node = start("final.log");
  ASSERT_TRUE(node);
  const auto present = listed();
  size_t found = 0;
  for (const auto& label : acknowledged)
    found += present.count(label);
  EXPECT_EQ(found, acknowledged.size());
  node->kill(SIGINT);
  EXPECT_TRUE(filesStartingWith(dir_, "objects.bin.tmp.").empty());
  EXPECT_TRUE(filesStartingWith(dir_, "objects.bin.refused").empty()) << "a memory was refused";
  // The figures the report quotes; the loop must have done its job.
  std::cout << "persistence: " << kills << " kill -9, " << acknowledged.size() << " learns acknowledged, " << found
            << " found after restart, " << present.size() << " objects in memory, " << temporaries_left
            << " kills landed in a save and left its temporary, " << planted
            << " more temporaries planted for kills that missed; all removed at the next start" << std::endl;
  // The loop did its job (a loaded machine gets fewer rounds: an odd round kills only after an acknowledged
  // learn, so about half as many learns as kills are acknowledged).
  EXPECT_GE(kills, 6);
  EXPECT_GE(acknowledged.size(), static_cast<size_t>(kills / 3));
  EXPECT_GE(temporaries_left, 1) << "no kill landed inside a save";
}

// A refused memory is kept aside under a timestamped name — a second refusal keeps the first copy — the
// log and diagnostics say where it went, and what is learned after the refusal survives a restart.
TEST_F(Persistence, ARefusedMemoryIsKeptAsideAndNeverOverwritten)
{
  const std::vector<std::string> garbage{std::string(3000, 'A'), std::string(2000, 'B')};
  std::vector<std::string> kept;
  for (size_t i = 0; i < garbage.size(); ++i)
  {
    writeFile(memory_file_, garbage[i]);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      diagnostics_.clear();
    }
    auto node = start("refused_" + std::to_string(i) + ".log");
    ASSERT_TRUE(node);
    kept = filesStartingWith(dir_, "objects.bin.refused-");
    ASSERT_EQ(kept.size(), i + 1) << node->log();
    const std::string where = diagnostic("refused memory kept as", 10.0);
    EXPECT_TRUE(std::find(kept.begin(), kept.end(), where) != kept.end()) << "diagnostics: " << where;
    EXPECT_NE(node->log().find(where), std::string::npos) << node->log();
    EXPECT_EQ(readFile(where), garbage[i]);
    EXPECT_TRUE(listed().empty());
    ASSERT_TRUE(learn("after_refusal_" + std::to_string(i)));
    node->kill(SIGKILL);
  }
  for (size_t i = 0; i < garbage.size(); ++i)
    EXPECT_EQ(std::count_if(kept.begin(), kept.end(), [&](const std::string& f) { return readFile(f) == garbage[i]; }),
              1)
        << "the copy of refusal " << i << " is lost";
  // Learned after the refusal, saved at the usual path: loaded at the next start.
  auto node = start("after_refusal.log");
  ASSERT_TRUE(node);
  EXPECT_EQ(listed(), (std::set<std::string>{"after_refusal_1"}));
  node->kill(SIGINT);
}

// A damaged or missing descriptor model stops the node — it cannot recognise anything — with a message
// that names the file and the problem (the nodelet loader alone exits 1 without a word).
TEST_F(Persistence, ADamagedDescriptorModelStopsTheNodeWithAClearMessage)
{
  const std::string good = readFile(std::string(BIOVISION_RECOGNITION_MODELS) + "/" +
                                    biovision_recognition::kDefaultModelFile);
  ASSERT_GT(good.size(), 1000u);
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x01;
  std::string foreign = good;
  foreign[0] = 'X';
  struct Case
  {
    const char* name;
    std::string bytes;
    const char* problem;
  };
  const std::vector<Case> cases{{"truncated", good.substr(0, good.size() / 2), "truncated"},
                                {"flipped", flipped, "checksum"},
                                {"foreign", foreign, "magic"},
                                {"missing", "", "cannot open"}};
  for (const auto& c : cases)
  {
    const std::string model = dir_ + "/model_" + c.name + ".bin";
    if (std::string(c.name) != "missing")
      writeFile(model, c.bytes);
    NodeProcess node({"_model_file:=" + model}, dir_ + "/model_" + c.name + ".log");
    const int status = node.wait(30.0);
    ASSERT_NE(status, -1) << c.name << ": the node kept running with a damaged model";
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << c.name << ": status " << status;
    const std::string log = node.log();
    EXPECT_NE(log.find(model), std::string::npos) << c.name << ": the log does not name the file:\n" << log;
    EXPECT_NE(log.find(c.problem), std::string::npos) << c.name << ": the log does not say '" << c.problem << "':\n"
                                                      << log;
  }
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "recognition_persistence_test", 0).run();  // fixtures spin
}
