// Unit tests of the ROS-free task manager (thesis §5.3.3): block buffers, recursion, time-outs, failure
// policies, the grid planner, mission parsing, and the simple macro-tasks on a kinematic point robot.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_tasks/exploration_planner.hpp"
#include "biovision_tasks/go_to_task.hpp"
#include "biovision_tasks/grid_planner.hpp"
#include "biovision_tasks/macro_task.hpp"
#include "biovision_tasks/mission_record.hpp"
#include "biovision_tasks/path_follower.hpp"
#include "biovision_tasks/search_task.hpp"
#include "biovision_tasks/task_manager.hpp"
#include "biovision_tasks/task_spec.hpp"

using namespace biovision_tasks;

namespace
{
// Counts its blocks' calls; succeeds when `done` is set, fails when `broken` is set.
class ProbeTask : public Task
{
public:
  explicit ProbeTask(std::string name, double timeout = 0) : Task(std::move(name), timeout) {}
  int started = 0, detected = 0, concluded = 0, acted = 0;
  bool done = false, broken = false;

protected:
  void onStart(const Percept&) override { ++started; }
  void onDetect(const Percept&) override { ++detected; }
  TaskState onConclude(const Percept&) override
  {
    ++concluded;
    return broken ? fail("broken") : done ? TaskState::Succeeded : TaskState::Running;
  }
  void onAct(const Percept&, MotorCommand& c) override
  {
    ++acted;
    c.base = MotorCommand::Base::Heading;
    c.head_mode = name();
  }
};

Percept at(double t, double x = 0, double y = 0, double yaw = 0)
{
  Percept p;
  p.time = t;
  p.pose = {x, y, yaw};
  p.pose_valid = true;
  return p;
}

TaskSpec spec(const std::string& text)
{
  return TaskSpec::parseText(text).at(0);
}

// A 10 m x 10 m room (origin -5, -5; 0.1 m cells; walls on its border) with a wall along x = 1 from y = -3 to
// y = 3.
OccupancyMap wallMap()
{
  cv::Mat1b cells(100, 100, uchar(0));
  cv::rectangle(cells, cv::Rect(0, 0, 100, 100), 100, 2);
  for (int r = 20; r < 80; ++r)
    for (int c = 60; c < 62; ++c)
      cells(r, c) = 100;
  return OccupancyMap(cells, -5, -5, 0.1);
}
}  // namespace

TEST(MacroTask, StepsRunInOrderAndTheLastSuccessIsTheMacroTasks)
{
  MacroTask m("m", 0);
  auto a = std::make_unique<ProbeTask>("a");
  auto b = std::make_unique<ProbeTask>("b");
  ProbeTask *pa = a.get(), *pb = b.get();
  m.addStep(std::move(a));
  m.addStep(std::move(b));
  m.start(at(0));
  EXPECT_EQ(m.microTask(), "a");
  MotorCommand c;
  m.act(at(0), c);
  EXPECT_EQ(c.head_mode, "a");
  EXPECT_EQ(pb->started, 0);
  pa->done = true;
  EXPECT_EQ(m.evaluate(at(1)), TaskState::Running);  // a succeeded: b starts in the same cycle
  EXPECT_EQ(pb->started, 1);
  EXPECT_EQ(m.microTask(), "b");
  EXPECT_EQ(m.step(), 1);
  pb->done = true;
  EXPECT_EQ(m.evaluate(at(2)), TaskState::Succeeded);
}

TEST(MacroTask, RecursionAndFailurePropagationNameTheStep)
{
  auto inner = std::make_unique<MacroTask>("inner", 0);
  auto x = std::make_unique<ProbeTask>("x");
  ProbeTask* px = x.get();
  inner->addStep(std::move(x));
  MacroTask outer("outer", 0);
  auto first = std::make_unique<ProbeTask>("first");
  first->done = true;
  outer.addStep(std::move(first));
  outer.addStep(std::move(inner));
  outer.start(at(0));
  EXPECT_EQ(outer.evaluate(at(0)), TaskState::Running);
  EXPECT_EQ(outer.microTask(), "x");  // the micro-task two levels down
  px->broken = true;
  EXPECT_EQ(outer.evaluate(at(1)), TaskState::Failed);
  EXPECT_EQ(outer.reason(), "step 2/2 (inner): step 1/1 (x): broken");
}

TEST(MacroTask, AnOptionalStepsFailureDoesNotFailTheSequence)
{
  MacroTask m("m", 0);
  auto a = std::make_unique<ProbeTask>("a");
  a->broken = true;
  auto b = std::make_unique<ProbeTask>("b");
  b->done = true;
  m.addStep(std::move(a), true);
  m.addStep(std::move(b));
  m.start(at(0));
  EXPECT_EQ(m.evaluate(at(0)), TaskState::Succeeded);
}

TEST(Task, TimeOutFailsWithAReasonAndCancelsTheRunningStep)
{
  MacroTask m("m", 5.0);
  auto a = std::make_unique<ProbeTask>("a");
  ProbeTask* pa = a.get();
  m.addStep(std::move(a));
  m.start(at(10));
  EXPECT_EQ(m.evaluate(at(14.9)), TaskState::Running);
  EXPECT_EQ(m.evaluate(at(15.1)), TaskState::Failed);
  EXPECT_EQ(m.reason(), "time-out after 5 s");
  EXPECT_EQ(pa->state(), TaskState::Cancelled);
  MotorCommand c;
  m.act(at(16), c);  // a finished task does not act
  EXPECT_EQ(pa->acted, 0);
}

TEST(TaskManager, OnlyTheHeadOfTheVisuomotorBufferActsWhileEveryDetectionRuns)
{
  TaskManager manager;
  // Three sequential waits: only the first is started and acts; all three detect.
  manager.add(spec("look_ahead duration=1"));
  manager.add(spec("look_around duration=1"));
  manager.add(spec("wait duration=1"));
  MotorCommand c = manager.step(at(0));
  EXPECT_EQ(c.head_mode, "look_ahead");
  EXPECT_EQ(manager.status().macro_task, "look_ahead");
  c = manager.step(at(1.0));  // the first is done: the second takes over in the same cycle
  EXPECT_EQ(c.head_mode, "explore");
  ASSERT_EQ(manager.finished().size(), 1u);
  EXPECT_EQ(manager.finished()[0].state, TaskState::Succeeded);
  manager.step(at(2.0));
  manager.step(at(3.0));
  EXPECT_TRUE(manager.idle());
  EXPECT_EQ(manager.finished().size(), 3u);
  EXPECT_EQ(manager.step(at(4)).base, MotorCommand::Base::Stop);  // idle: the base stops
}

TEST(TaskManager, DetectionOfWaitingTasksCountsWhenTheirTurnComes)
{
  TaskManager manager;
  manager.add(spec("wait duration=10"));
  manager.add(spec("search cup"));
  Percept p = at(0);
  p.seen.push_back({"cup", 2.0, 1.0, 0.9, 0.0});
  p.seen.push_back({"cup", 2.1, 1.0, 0.9, 0.2});  // the second sighting confirms the first
  manager.step(p);                                // the search is not active yet, but its detection sees the cup
  EXPECT_EQ(manager.status().macro_task, "wait");
  manager.step(at(10.5));  // the wait ends; the search starts and concludes at once
  EXPECT_TRUE(manager.idle());
  ASSERT_EQ(manager.finished().size(), 2u);
  EXPECT_EQ(manager.finished()[1].name, "search cup");
  EXPECT_EQ(manager.finished()[1].state, TaskState::Succeeded);
  EXPECT_DOUBLE_EQ(manager.record().found.at("cup").x, 2.1);
}

TEST(TaskManager, HigherPriorityTakesTheVisuomotorCycleAndConcurrentConclusionsRun)
{
  TaskManager manager;
  manager.add(spec("look_around duration=100"));
  EXPECT_EQ(manager.step(at(0)).head_mode, "explore");
  manager.add(spec("look_ahead duration=2 priority=5"));
  EXPECT_EQ(manager.step(at(1)).head_mode, "look_ahead");
  EXPECT_EQ(manager.step(at(3.5)).head_mode, "explore");  // back to the preempted task
  // A concurrent task concludes while another drives.
  manager.add(spec("wait duration=1 concurrent=true priority=-1"));
  manager.step(at(4));
  manager.step(at(5.5));
  ASSERT_EQ(manager.finished().size(), 2u);
  EXPECT_EQ(manager.finished()[1].name, "wait");
  EXPECT_EQ(manager.status().macro_task, "look_around");
}

TEST(TaskManager, FailurePoliciesContinueAbortOrFallBack)
{
  {  // abort: the rest is cancelled
    TaskManager m;
    m.add(spec("search ghost timeout=5 on_failure=abort"));
    m.add(spec("wait duration=1"));
    m.step(at(0));
    m.step(at(6));
    EXPECT_TRUE(m.idle());
    ASSERT_EQ(m.finished().size(), 2u);
    EXPECT_EQ(m.finished()[0].reason, "object 'ghost' never found in 5 s");
    EXPECT_EQ(m.finished()[1].state, TaskState::Cancelled);
  }
  {  // fallback: return home replaces the rest
    TaskManager m;
    m.add(spec("search ghost timeout=5 on_failure=return_home"));
    m.add(spec("wait duration=100"));
    m.step(at(0, 0, 0));
    m.step(at(6, 3, 0));
    EXPECT_EQ(m.status().macro_task, "return_home");
    const MotorCommand c = m.step(at(6.1, 3, 0));
    EXPECT_EQ(c.base, MotorCommand::Base::Goal);
    EXPECT_NEAR(c.goal_x, 0.0, 1e-9);  // home is the first localised pose
    m.step(at(7, 0.1, 0));
    EXPECT_TRUE(m.idle());
    EXPECT_EQ(m.finished().back().state, TaskState::Succeeded);
  }
}

TEST(TaskManager, NoLocalisationStopsTheBaseAndCancelEndsATask)
{
  TaskManager m;
  const int id = m.add(spec("go_to x=3 y=0"));
  Percept lost = at(0);
  lost.pose_valid = false;
  EXPECT_EQ(m.step(lost).base, MotorCommand::Base::Stop);
  EXPECT_TRUE(m.cancel(id, "user"));
  EXPECT_FALSE(m.cancel(id, "user"));
  EXPECT_EQ(m.finished().back().state, TaskState::Cancelled);
  EXPECT_EQ(m.status().message, "user");
}

TEST(GoToTask, UnknownObjectFailsNamingItAndATrappedBaseFailsAfterTheTimeout)
{
  TaskManager m;
  m.add(spec("go_to teapot"));
  m.step(at(0));
  EXPECT_EQ(m.finished().back().reason, "object 'teapot' was neither found in this mission nor is it in memory");
  TaskParameters p;
  p.trapped_timeout = 5;
  TaskManager m2(p);
  m2.add(spec("go_to x=5 y=0"));
  Percept trapped = at(0);
  trapped.base_trapped = true;
  for (double t = 0; t <= 6; t += 0.5)
  {
    trapped.time = t;
    m2.step(trapped);
  }
  ASSERT_FALSE(m2.finished().empty());
  EXPECT_EQ(m2.finished().back().state, TaskState::Failed);
  EXPECT_NE(m2.finished().back().reason.find("trapped"), std::string::npos);
}

TEST(GridPlanner, GoesAroundAWallAndKeepsClearOfIt)
{
  const OccupancyMap map = wallMap();
  GridPlanner::Options o;
  const auto path = GridPlanner::plan(map, {-2, 0}, {3, 0}, o);
  ASSERT_FALSE(path.empty());
  EXPECT_NEAR(path.back().x, 3, 1e-9);
  // Every straight leg stays clear of the wall cells (x 1.0..1.2, y -3..3) by the inflation radius.
  cv::Point2d from(-2, 0);
  for (const auto& to : path)
  {
    for (double s = 0; s <= 1; s += 0.01)
    {
      const cv::Point2d q = from + (to - from) * s;
      const double dx = std::max({1.0 - q.x, 0.0, q.x - 1.2}), dy = std::max({-3.0 - q.y, 0.0, q.y - 3.0});
      EXPECT_GE(std::hypot(dx, dy), o.radius - 0.1) << q;
    }
    from = to;
  }
}

namespace
{
// A 6 x 6 m map (0.1 m cells) with a wall along y = 3.05 m; `gaps` are the free column ranges [first, last].
OccupancyMap wallWithGaps(const std::vector<std::pair<int, int>>& gaps)
{
  cv::Mat1b cells(60, 60, uchar(0));
  for (int c = 0; c < 60; ++c)
  {
    bool open = false;
    for (const auto& [first, last] : gaps)
      open = open || (c >= first && c <= last);
    if (!open)
      cells(30, c) = 100;
  }
  return OccupancyMap(cells, 0, 0, 0.1);
}
}  // namespace

TEST(OccupancyMap, CellsWithinABoxAreClippedToTheMap)
{
  const OccupancyMap m(cv::Mat1b(20, 30, uchar(0)), -1.0, -2.0, 0.1);  // x in [-1, 2), y in [-2, 0)
  EXPECT_EQ(m.cellsWithin(0.0, -1.0, 0.25, -0.75), cv::Rect(10, 10, 3, 3));
  EXPECT_EQ(m.cellsWithin(0.25, -0.75, 0.0, -1.0), cv::Rect(10, 10, 3, 3)) << "corners in any order";
  EXPECT_EQ(m.cellsWithin(-5.0, -5.0, 5.0, 5.0), cv::Rect(0, 0, 30, 20)) << "clipped";
  EXPECT_TRUE(m.cellsWithin(3.0, -1.0, 4.0, -0.5).empty()) << "right of the map";
  EXPECT_TRUE(m.cellsWithin(-3.0, -1.0, -2.0, -0.5).empty()) << "left of the map";
  EXPECT_EQ(m.cellsWithin(-1e300, -1e300, 1e300, 1e300), cv::Rect(0, 0, 30, 20)) << "no int overflow";
  EXPECT_TRUE(m.cellsWithin(NAN, -1.0, 0.0, 0.0).empty());
  EXPECT_TRUE(OccupancyMap().cellsWithin(0, 0, 1, 1).empty());
}

TEST(OccupancyMap, ObstacleDistanceIsExactToTheNearestObstacleCentre)
{
  const OccupancyMap map = wallWithGaps({{27, 33}});
  const cv::Mat1f d = map.obstacleDistance(40);
  EXPECT_NEAR(d(30, 30), 0.4, 1e-4);  // the gap's middle: 4 cells from both ends
  EXPECT_NEAR(d(30, 26), 0.0, 1e-4);
  EXPECT_NEAR(d(34, 26), 0.4, 1e-4);  // straight above the wall
  EXPECT_NEAR(d(33, 29), std::hypot(0.3, 0.3), 1e-3);
  // Weak cells and unknown cells are free; with no obstacle the distance is large.
  cv::Mat1b weak(10, 10, uchar(20));
  weak(0, 0) = OccupancyMap::kUnknown;
  EXPECT_GE(OccupancyMap(weak, 0, 0, 0.1).obstacleDistance(40)(5, 5), 1.0f);
}

TEST(GridPlanner, SqueezesThroughAGapNarrowerThanTheMarginButWiderThanTheRobot)
{
  // Occupied cell centres 0.8 m apart: no free cell keeps 0.41 m, the middle one keeps 0.4 m.
  const OccupancyMap map = wallWithGaps({{27, 33}});
  GridPlanner::Options o;  // radius 0.41, no squeeze
  const cv::Point2d start(3.05, 1.0), goal(3.05, 5.0);
  cv::Mat1b sight(1, 1, uchar(7));
  EXPECT_TRUE(GridPlanner::plan(map, start, goal, o, &sight).empty());
  EXPECT_TRUE(sight.empty()) << "no path, no mask";
  o.lethal_radius = 0.31;
  const auto path = GridPlanner::plan(map, start, goal, o, &sight);
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(path.back(), goal);
  ASSERT_EQ(sight.size(), map.cells().size());
  // Every leg keeps the lethal radius (less half a cell of line rasterisation) from the wall cells and
  // crosses the wall's row through the gap.
  const cv::Mat1f distance = map.obstacleDistance(40);
  cv::Point2d from = start;
  bool crossed = false;
  for (const auto& to : path)
  {
    for (double s = 0; s <= 1; s += 0.005)
    {
      const cv::Point2d q = from + (to - from) * s;
      int r, c;
      ASSERT_TRUE(map.cellOf(q.x, q.y, r, c));
      EXPECT_GE(distance(r, c), o.lethal_radius - 0.05) << q;
      if (r == 30)
      {
        crossed = true;
        EXPECT_EQ(c, 30) << q;
      }
    }
    from = to;
  }
  EXPECT_TRUE(crossed);
  // The planner's own lineOfSight agrees with the legs it returned.
  from = start;
  for (const auto& to : path)
  {
    EXPECT_TRUE(GridPlanner::lineOfSight(map, sight, from, to)) << from << " -> " << to;
    from = to;
  }
  // A goal within the lethal radius of the wall has no path.
  EXPECT_TRUE(GridPlanner::plan(map, start, {2.0, 3.25}, o).empty());
}

TEST(GridPlanner, AStartInsideTheInflationLeavesItWithoutGettingCloser)
{
  // The robot stands 0.2 m from a wall (inside the 0.41 m inflation), 1 m beside a 2 m gap; the goal is
  // beyond the gap. The way there never comes nearer the wall than the start: it used to run along the
  // wall inside the inflation, closer still, towards the gap's edge.
  const OccupancyMap map = wallWithGaps({{20, 39}});
  GridPlanner::Options o;
  const cv::Point2d start(1.05, 2.85), goal(3.05, 4.5);
  const auto path = GridPlanner::plan(map, start, goal, o);
  ASSERT_FALSE(path.empty());
  const cv::Mat1f distance = map.obstacleDistance(40);
  int r, c;
  ASSERT_TRUE(map.cellOf(start.x, start.y, r, c));
  const float at_start = distance(r, c);
  ASSERT_LT(at_start, o.radius);
  cv::Point2d from = start;
  for (const auto& to : path)
  {
    for (double s = 0; s <= 1; s += 0.01)
    {
      const cv::Point2d q = from + (to - from) * s;
      ASSERT_TRUE(map.cellOf(q.x, q.y, r, c));
      EXPECT_GE(distance(r, c), at_start - 1e-4) << q;
    }
    from = to;
  }
}

TEST(GridPlanner, AWideWayRoundIsPreferredToASqueeze)
{
  // The narrow gap of the last test and a 2 m wide one 2 m further on.
  const OccupancyMap map = wallWithGaps({{27, 33}, {50, 59}});
  GridPlanner::Options o;
  const cv::Point2d start(3.05, 1.0), goal(3.05, 5.0);
  const auto wide = GridPlanner::plan(map, start, goal, o);
  ASSERT_FALSE(wide.empty());
  o.lethal_radius = 0.31;
  const auto with_squeeze = GridPlanner::plan(map, start, goal, o);
  ASSERT_EQ(with_squeeze.size(), wide.size());
  for (size_t i = 0; i < wide.size(); ++i)
    EXPECT_EQ(with_squeeze[i], wide[i]);
  EXPECT_TRUE(std::any_of(wide.begin(), wide.end(), [](const cv::Point2d& p) { return p.x > 4.9; }))
      << "the path goes through the wide gap";
}

TEST(GridPlanner, OptionsForTheTaskParametersSqueezeOnlyInsideTheMargin)
{
  TaskParameters p;
  GridPlanner::Options o = GridPlanner::optionsFor(p);
  EXPECT_DOUBLE_EQ(o.radius, p.robot_radius + p.inflation_margin);
  EXPECT_DOUBLE_EQ(o.lethal_radius, p.robot_radius + p.squeeze_margin);
  EXPECT_EQ(o.occupied_threshold, p.occupied_threshold);
  p.squeeze_margin = p.inflation_margin;
  EXPECT_EQ(GridPlanner::optionsFor(p).lethal_radius, 0.0);
}

namespace
{
// At (-4, 0) looking east in a 10 m square room walled round (its LTM: 100 x 100 cells of 0.1 m from (-5, -5)).
Percept inWalledRoom(cv::Mat1b& cells)
{
  Percept p;
  p.pose_valid = true;
  p.pose = {-4.0, 0.0, 0.0};
  p.view_yaw = 0.0;
  cells = cv::Mat1b(100, 100, uchar(0));
  cv::rectangle(cells, cv::Rect(0, 0, 100, 100), 100, 2);
  p.map = OccupancyMap(cells, -5, -5, 0.1);
  return p;
}
}  // namespace

TEST(ExplorationPlanner, HeadsForAFrontierOfWhatTheCameraSawButNotOneBehindAWall)
{
  TaskParameters parameters;
  cv::Mat1b cells;
  Percept p = inWalledRoom(cells);
  ExplorationPlanner open(parameters);
  open.recordVisit(p);
  cv::Point2d goal;
  ASSERT_TRUE(open.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_TRUE(open.seen(goal));
  const double d = std::hypot(goal.x + 4.0, goal.y);
  EXPECT_GE(d, 2 * parameters.visit_cell);
  EXPECT_LE(d, parameters.view_range + parameters.visit_cell);
  const double c = parameters.visit_cell;
  EXPECT_TRUE(!open.seen(goal + cv::Point2d(c, 0)) || !open.seen(goal - cv::Point2d(c, 0)) ||
              !open.seen(goal + cv::Point2d(0, c)) || !open.seen(goal - cv::Point2d(0, c)))
      << "a frontier has an unseen neighbour";
  EXPECT_FALSE(open.seen({3.0, 0.0})) << "beyond view_range";

  // Walled in: the view (now 3 m, all round) stops at the walls and every unseen neighbour lies behind one.
  cv::rectangle(cells, cv::Rect(5, 35, 26, 30), 100, 1);  // x -4.5..-1.9, y -1.5..1.5 round the robot
  p.map = OccupancyMap(cells, -5, -5, 0.1);
  p.view_yaw = std::numeric_limits<double>::quiet_NaN();
  parameters.view_range = 3.0;
  ExplorationPlanner boxed(parameters);
  boxed.recordVisit(p);
  EXPECT_TRUE(boxed.seen({-2.25, 1.25}));
  EXPECT_FALSE(boxed.seen({-1.25, 0.0}));
  EXPECT_FALSE(boxed.frontier(p, {-4.0, 0.0}, goal)) << goal.x << ", " << goal.y;
  // The same box with a door in its east wall: the doorway is a frontier.
  cv::line(cells, {30, 45}, {30, 54}, 0);  // y -0.5..0.4 at x = -2.0
  p.map = OccupancyMap(cells, -5, -5, 0.1);
  ExplorationPlanner door(parameters);
  door.recordVisit(p);
  ASSERT_TRUE(door.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_GT(goal.x, -2.5);
  EXPECT_LT(std::abs(goal.y), 1.0);

  parameters.view_range = 0;  // boredom only
  ExplorationPlanner off(parameters);
  p.map = OccupancyMap(cv::Mat1b(100, 100, uchar(0)), -5, -5, 0.1);
  off.recordVisit(p);
  EXPECT_FALSE(off.frontier(p, {-4.0, 0.0}, goal));
}

TEST(ExplorationPlanner, ABoredomGoalBeyondTheMapIsNotBehindAKnownWall)
{
  // A corridor along x whose map ends 0.3 m beyond its walls; the robot faces the left wall. Boredom's
  // candidate straight ahead lies outside the map, so nothing blocked it: make demo drove at goals 1 m
  // behind the corridor's walls.
  TaskParameters parameters;
  parameters.view_range = 0;  // boredom only
  parameters.explore_step = 3.0;
  cv::Mat1b cells(30, 60, uchar(0));
  cells.row(2).setTo(100);   // y = -1.25
  cells.row(27).setTo(100);  // y = +1.25
  Percept p = at(1.0, 1.0, 0.0, M_PI / 2);
  p.map = OccupancyMap(cells, -1.0, -1.5, 0.1);
  ExplorationPlanner planner(parameters);
  planner.recordVisit(p);
  cv::Point2d goal;
  ASSERT_TRUE(planner.nextGoal(p, {1.0, 0.0}, goal));
  EXPECT_LT(std::abs(goal.y), 1.2) << goal.x << ", " << goal.y;
}

TEST(ExplorationPlanner, AnUnreachableFrontierIsTriedAgainLaterAndLessOftenEachTime)
{
  // A base wedged at one spot once struck off every frontier of the room for good, one each 2.4 s, and never
  // explored the target's side (mission_eval report seeds 4, 6, 42).
  TaskParameters parameters;
  cv::Mat1b cells;
  Percept p = inWalledRoom(cells);
  ExplorationPlanner planner(parameters);
  planner.recordVisit(p);
  cv::Point2d first;
  ASSERT_TRUE(planner.frontier(p, {-4.0, 0.0}, first));
  planner.markUnreachable(first, p.time);
  EXPECT_EQ(planner.visits(first), 0.0) << "a failure is no time spent there";
  EXPECT_DOUBLE_EQ(planner.boredom(first), ExplorationPlanner::kUnreachableBoredom);
  cv::Point2d goal;
  ASSERT_TRUE(planner.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_GT(std::hypot(goal.x - first.x, goal.y - first.y), parameters.visit_cell) << "struck off for now";
  p.time += parameters.frontier_retry_time;
  ASSERT_TRUE(planner.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_EQ(goal, first) << "tried again after frontier_retry_time";
  planner.markUnreachable(first, p.time);
  p.time += 1.5 * parameters.frontier_retry_time;
  ASSERT_TRUE(planner.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_NE(goal, first) << "the second failure strikes it off twice as long";
  p.time += 0.5 * parameters.frontier_retry_time;
  ASSERT_TRUE(planner.frontier(p, {-4.0, 0.0}, goal));
  EXPECT_EQ(goal, first);
  EXPECT_DOUBLE_EQ(planner.boredom(first), 2 * ExplorationPlanner::kUnreachableBoredom);
}

TEST(ExplorationPlanner, IgnoresPosesThatAreNotFiniteOrFarOutside)
{
  // A pose_valid percept with a NaN, infinite or absurd position (a broken localisation) once gave a cell
  // index by an overflowing cast: a "frontier" a billion metres away, or undefined behaviour.
  TaskParameters parameters;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const Percept::Pose& bad : std::vector<Percept::Pose>{
           {nan, 0, 0}, {0, nan, 0}, {inf, 0, 0}, {0, -inf, 0}, {1e12, 0, 0}, {0, -1e300, 0}, {0, 0, nan}})
  {
    ExplorationPlanner planner(parameters);
    Percept p = at(1.0, bad.x, bad.y, bad.yaw);
    p.view_yaw = 0.0;
    planner.recordVisit(p);
    p.time = 2.0;
    planner.recordVisit(p);
    if (!std::isfinite(bad.x) || !std::isfinite(bad.y) || std::abs(bad.x) + std::abs(bad.y) > 1e6)
      planner.markUnreachable({bad.x, bad.y}, 2.0);  // a goal there (only the yaw case has a good position)
    EXPECT_EQ(planner.seenCells(), 0u) << bad.x << ", " << bad.y << ", " << bad.yaw;
    EXPECT_EQ(planner.visitedCells(), 0u) << bad.x << ", " << bad.y << ", " << bad.yaw;
    EXPECT_FALSE(planner.seen({bad.x, bad.y}));
    EXPECT_EQ(planner.visits({bad.x, bad.y}), 0.0);
    EXPECT_EQ(planner.boredom({bad.x, bad.y}), 0.0);
    cv::Point2d goal(7, 7);
    EXPECT_FALSE(planner.nextGoal(p, {0, 0}, goal));
    EXPECT_FALSE(planner.frontier(at(3.0), {0, 0}, goal)) << "goal " << goal.x << ", " << goal.y;
    EXPECT_EQ(goal, cv::Point2d(7, 7));
  }
}

TEST(ExplorationPlanner, CoverageMemoryStaysBoundedOverALongDrive)
{
  // Driving on and on through an unmapped world (or a big map) keeps adding seen cells; a robot left exploring
  // for days must not grow without bound. 40 m of all-round view at 0.2 m cells is ~31000 cells a look.
  TaskParameters parameters;
  parameters.view_range = 20.0;
  parameters.visit_cell = 0.2;
  ExplorationPlanner planner(parameters);
  size_t most = 0;
  double x = 0;
  for (int k = 0; k < 30; ++k, x += 20.0)  // 600 m east, a look every 20 m (~20000 new cells each)
  {
    planner.recordVisit(at(k, x, 0.0));
    most = std::max(most, planner.seenCells());
  }
  EXPECT_LE(most, ExplorationPlanner::kMaxCells);
  EXPECT_GT(most, ExplorationPlanner::kMaxCells / 2) << "the cap was reached, not the drive too short";
  // What is round the robot is kept, the start (580 m back) forgotten; the frontier is still ahead or beside.
  EXPECT_TRUE(planner.seen({x - 20.0, 0.0}));
  EXPECT_TRUE(planner.seen({x - 20.0 + 15.0, 0.0}));
  EXPECT_FALSE(planner.seen({0.0, 0.0}));
  cv::Point2d goal;
  ASSERT_TRUE(planner.frontier(at(30, x - 20.0, 0.0), {0, 0}, goal));
  EXPECT_LT(std::hypot(goal.x - (x - 20.0), goal.y), parameters.view_range + parameters.visit_cell);

  // The visit times too (a robot wandering for ever at 1 s a cell).
  parameters.view_range = 0;
  ExplorationPlanner wanderer(parameters);
  for (int k = 0; k < 300000; ++k)
    wanderer.recordVisit(at(k, 0.2 * k, 0.2 * (k % 7)));
  EXPECT_LE(wanderer.visitedCells(), ExplorationPlanner::kMaxCells);
  EXPECT_GT(wanderer.visits({0.2 * 299999, 0.2 * (299999 % 7)}), 0.0);
}

namespace
{
// The base drove home -> (0, 2) -> (3, 2) (0.05 m every 0.1 s); return_home is added. Returns the time.
double driveTheTrailOut(TaskManager& m)
{
  double t = 0;
  for (double y = 0; y <= 2.0; y += 0.05, t += 0.1)
    m.step(at(t, 0, y));
  for (double x = 0; x <= 3.0; x += 0.05, t += 0.1)
    m.step(at(t, x, 2.0));
  m.add(spec("return_home"));
  return t;
}
}  // namespace

TEST(GoToTask, ReturnHomeTrappedRetracesTheTrailDrivenThenFailsWhenTrappedAgain)
{
  // The straight way back is blocked by something the map does not hold (mission_eval tune seeds 131, 165:
  // a new obstacle beside the straight line home).
  TaskParameters p;
  p.trapped_timeout = 5;
  TaskManager m(p);
  double t = driveTheTrailOut(m);
  Percept trapped = at(t, 3.0, 2.0);
  trapped.base_trapped = true;
  MotorCommand c = m.step(trapped);
  EXPECT_NEAR(c.goal_x, 0.0, 1e-9) << "no map: straight home first";
  EXPECT_NEAR(c.goal_y, 0.0, 1e-9);
  const double start = t;
  for (; t < start + 6.25; t += 0.5)  // trapped for longer than trapped_timeout
  {
    trapped.time = t;
    c = m.step(trapped);
  }
  ASSERT_TRUE(m.finished().empty()) << "failed at once: " << m.finished().back().reason;
  ASSERT_EQ(c.base, MotorCommand::Base::Goal);
  EXPECT_NEAR(c.goal_y, 2.0, 0.05) << "the trail back runs along y = 2 first, not straight home";
  EXPECT_LT(c.goal_x, 3.0);
  for (; t < start + 13.25; t += 0.5)  // and as long again on the trail
  {
    trapped.time = t;
    m.step(trapped);
  }
  ASSERT_FALSE(m.finished().empty());
  EXPECT_EQ(m.finished().back().state, TaskState::Failed);
  EXPECT_NE(m.finished().back().reason.find("trapped for 5 s on the trail back"), std::string::npos)
      << m.finished().back().reason;
}

TEST(GoToTask, ReturnHomeRetracesTheTrailRoundWhatTheMapNowHoldsOnIt)
{
  // The same trail with a new crate on it at (2.0, 2.0), 0.4 m wide, now in the map: no trail point the base
  // would have to stand in it for is handed to the base (make demo: sent into the crate, trapped again).
  TaskParameters p;
  p.trapped_timeout = 5;
  TaskManager m(p);
  double t = driveTheTrailOut(m);
  cv::Mat1b cells(50, 50, uchar(0));         // 0.1 m cells from (-1, -1)
  cells(cv::Rect(28, 28, 4, 4)).setTo(100);  // x, y in [1.8, 2.2)
  Percept trapped = at(t, 3.0, 2.0);
  trapped.map = OccupancyMap(cells, -1.0, -1.0, 0.1);
  trapped.base_trapped = true;
  MotorCommand c;
  bool on_trail = false;
  for (const double start = t; t < start + 10.25; t += 0.5)
  {
    trapped.time = t;
    c = m.step(trapped);
    if (t > start + 5.5)
    {
      ASSERT_TRUE(m.finished().empty()) << m.finished().back().reason;
      on_trail = true;
      const double to_crate = std::hypot(std::max(std::abs(c.goal_x - 2.0) - 0.2, 0.0),
                                         std::max(std::abs(c.goal_y - 2.0) - 0.2, 0.0));
      EXPECT_GT(to_crate, p.robot_radius) << "goal " << c.goal_x << ", " << c.goal_y;
    }
  }
  EXPECT_TRUE(on_trail);
  EXPECT_LT(c.goal_x, 3.0);
}

TEST(GoToTask, TheTrailBackGoesRoundTheNewObstacleNotStraightPastIt)
{
  // As above: the crate on the trail at (2.0, 2.0). Once the trail is taken, the base drives to each goal it
  // is given; no stretch between them may take its body over the crate (make demo: the trail points near
  // the crate dropped, the base was sent straight past its corner and trapped again).
  TaskParameters p;
  p.trapped_timeout = 5;
  TaskManager m(p);
  double t = driveTheTrailOut(m);
  cv::Mat1b cells(50, 50, uchar(0));
  cells(cv::Rect(28, 28, 4, 4)).setTo(100);  // x, y in [1.8, 2.2)
  Percept percept = at(t, 3.0, 2.0);
  percept.map = OccupancyMap(cells, -1.0, -1.0, 0.1);
  percept.base_trapped = true;
  MotorCommand c;
  for (const double start = t; t < start + 5.75; t += 0.5)
  {
    percept.time = t;
    c = m.step(percept);
  }
  ASSERT_TRUE(m.finished().empty()) << m.finished().back().reason;
  auto clearance = [](cv::Point2d a, cv::Point2d b) {  // least distance of the segment a-b to the crate
    double least = INFINITY;
    for (int i = 0; i <= 200; ++i)
    {
      const cv::Point2d q = a + (b - a) * (i / 200.0);
      least = std::min(least,
                       std::hypot(std::max(std::abs(q.x - 2.0) - 0.2, 0.0), std::max(std::abs(q.y - 2.0) - 0.2, 0.0)));
    }
    return least;
  };
  percept.base_trapped = false;
  cv::Point2d here(3.0, 2.0);
  int goals = 0;
  for (; goals < 100 && m.finished().empty(); ++goals, t += 0.5)
  {
    ASSERT_EQ(c.base, MotorCommand::Base::Goal);
    const cv::Point2d goal(c.goal_x, c.goal_y);
    EXPECT_GT(clearance(here, goal), p.robot_radius) << "from " << here << " to " << goal;
    here = goal;  // the base drives there
    percept.time = t;
    percept.pose = {here.x, here.y, 0.0};
    c = m.step(percept);
  }
  ASSERT_FALSE(m.finished().empty()) << "home never reached";
  EXPECT_EQ(m.finished().back().state, TaskState::Succeeded) << m.finished().back().reason;
  EXPECT_GT(goals, 2);
}

TEST(MissionRecord, TheTrailIsSpacedBoundedAndItsWayBackCutsLoops)
{
  MissionRecord r;
  for (int i = 0; i <= 200; ++i)
    r.extendTrail(0.05 * i, 0);
  EXPECT_GE(r.trail.size(), 40u);  // one point every 0.2-0.25 m of the 10 m
  for (size_t i = 1; i < r.trail.size(); ++i)
  {
    EXPECT_GE(r.trail[i].x - r.trail[i - 1].x, MissionRecord::kTrailSpacing - 1e-9);
    EXPECT_LE(r.trail[i].x - r.trail[i - 1].x, MissionRecord::kTrailSpacing + 0.05 + 1e-9);
  }
  MissionRecord longest;
  for (int i = 0; i < 3 * static_cast<int>(MissionRecord::kMaxTrail); ++i)
    longest.extendTrail(0.3 * i, 0);
  EXPECT_LE(longest.trail.size(), MissionRecord::kMaxTrail);
  EXPECT_EQ(longest.trail.front(), cv::Point2d(0, 0)) << "home stays the trail's first point";
  EXPECT_NEAR(longest.trail.back().x, 0.3 * (3 * MissionRecord::kMaxTrail - 1), 1e-9);
  // Out to x = 4, back to x = 2 and up to (2, 3): the way back from there skips the excursion to x = 4.
  MissionRecord loop;
  for (double x = 0; x <= 4.0; x += 0.05)
    loop.extendTrail(x, 0);
  for (double x = 4.0; x >= 2.0; x -= 0.05)
    loop.extendTrail(x, 0.1);
  for (double y = 0.1; y <= 3.0; y += 0.05)
    loop.extendTrail(2.0, y);
  const auto back = loop.wayBack({2.1, 3.1});
  ASSERT_GE(back.size(), 2u);
  EXPECT_NEAR(back.front().x, 2.0, 1e-9);
  EXPECT_NEAR(back.front().y, 3.0, 0.2);
  EXPECT_EQ(back.back(), cv::Point2d(0, 0));
  for (const auto& w : back)
    EXPECT_LT(w.x, 2.3) << "the loop to x = 4 is cut";
  for (size_t i = 1; i < back.size(); ++i)
    EXPECT_LT(std::hypot(back[i].x - back[i - 1].x, back[i].y - back[i - 1].y), 0.41) << "a jump across open ground";
  EXPECT_TRUE(MissionRecord().wayBack({1, 1}).empty());
  const size_t before = r.trail.size();
  r.extendTrail(std::nan(""), 50.0);
  r.extendTrail(20.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.trail.size(), before) << "a non-finite pose never enters the trail";
}

TEST(PathFollower, AFixedRouteIsFollowedWithoutReplanning)
{
  TaskParameters parameters;
  Percept p;
  p.pose_valid = true;
  p.pose = {0.0, 0.0, 0.0};
  p.map = wallMap();
  PathFollower follower(parameters);
  const std::vector<cv::Point2d> route{{0.0, 0.0}, {0.0, 1.0}, {0.0, 2.0}, {-1.0, 2.0}};
  follower.followRoute(route);
  EXPECT_TRUE(follower.followingRoute());
  EXPECT_EQ(follower.waypoint(p), route[1]) << "the first point, where the base is, is passed";
  p.time = 10 * parameters.replan_period;
  follower.blockAhead(p);
  EXPECT_EQ(follower.waypoint(p), route[1]) << "no replanning, blocked or not";
  p.pose = {0.0, 1.2, 0.0};  // within waypoint_tolerance of route[1]
  EXPECT_EQ(follower.waypoint(p), route[2]);
  EXPECT_EQ(follower.goal(), route.back());
  follower.setGoal({2.0, 0.0});
  EXPECT_FALSE(follower.followingRoute());
}

TEST(PathFollower, BlockAheadPlansRoundWhatStopsTheBase)
{
  TaskParameters parameters;
  Percept p;
  p.pose_valid = true;
  p.pose = {-2.0, 0.0, 0.0};
  p.map = OccupancyMap(cv::Mat1b(100, 100, uchar(0)), -5, -5, 0.1);
  PathFollower follower(parameters);
  follower.setGoal({2.0, 0.0});
  const cv::Point2d straight = follower.waypoint(p);
  EXPECT_NEAR(straight.x, 2.0, 1e-9);
  EXPECT_NEAR(straight.y, 0.0, 1e-9);
  follower.blockAhead(p);  // something 0.7 m towards the waypoint that the LTM does not hold
  follower.waypoint(p);
  ASSERT_GE(follower.waypoints().size(), 2u);
  double widest = 0;
  for (const cv::Point2d& w : follower.waypoints())
  {
    widest = std::max(widest, std::abs(w.y));
    EXPECT_GT(std::hypot(w.x + 1.3, w.y), 0.5) << "no waypoint on the blocked disc at (-1.3, 0)";
  }
  EXPECT_GT(widest, 2 * parameters.robot_radius) << "the way leads round it";
  EXPECT_NEAR(follower.waypoints().back().x, 2.0, 1e-9);
  follower.setGoal({2.0, 1.0});  // a new goal forgets the blocked discs
  EXPECT_EQ(follower.waypoint(p), cv::Point2d(2.0, 1.0));
}

TEST(PathFollower, AWaypointTheBaseStopsAtIsPassedEvenWithoutASightLineToTheNext)
{
  // The base stops within its own goal tolerance (0.2 m) of a waypoint; one held there because the straight
  // line on to the next crosses the inflation of a wall beside it parked the base until the task failed
  // (mission_eval tune seed 129).
  TaskParameters parameters;
  cv::Mat1b cells(100, 100, uchar(0));
  cv::rectangle(cells, cv::Rect(49, 0, 3, 60), 100, cv::FILLED);  // a wall along x = 0 from y = -5 to 1
  const OccupancyMap map(cells, -5, -5, 0.1);
  Percept p;
  p.pose_valid = true;
  p.pose = {-2.0, -2.0, 0.0};
  p.map = map;
  PathFollower follower(parameters);
  follower.setGoal({2.0, -2.0});
  follower.waypoint(p);
  const std::vector<cv::Point2d> plan = follower.waypoints();
  ASSERT_GE(plan.size(), 3u) << "the way leads round the wall's end";
  const cv::Mat1b blocked = map.inflatedObstacles(40, parameters.robot_radius + parameters.inflation_margin);
  // Beside the first waypoint, closer than goal_tolerance, where the line on to the second is not free.
  bool placed = false;
  for (int k = 0; k < 16 && !placed; ++k)
  {
    const double a = k * M_PI / 8, r = 0.8 * parameters.goal_tolerance;
    const cv::Point2d here = plan[0] + cv::Point2d(r * std::cos(a), r * std::sin(a));
    if (GridPlanner::lineOfSight(map, blocked, here, plan[1]))
      continue;
    placed = true;
    p.pose = {here.x, here.y, 0.0};
  }
  ASSERT_TRUE(placed) << "no spot beside " << plan[0].x << ", " << plan[0].y << " without a sight line";
  EXPECT_EQ(follower.waypoint(p), plan[1]);
  // Farther than goal_tolerance (but within waypoint_tolerance) the sight line still decides: no corner cut.
  PathFollower again(parameters);
  p.pose = {-2.0, -2.0, 0.0};
  again.setGoal({2.0, -2.0});
  again.waypoint(p);
  ASSERT_EQ(again.waypoints(), plan);
  for (int k = 0; k < 16; ++k)
  {
    const double a = k * M_PI / 8, r = 0.5 * (parameters.goal_tolerance + parameters.waypoint_tolerance);
    const cv::Point2d here = plan[0] + cv::Point2d(r * std::cos(a), r * std::sin(a));
    if (!GridPlanner::lineOfSight(map, blocked, here, plan[1]))
    {
      p.pose = {here.x, here.y, 0.0};
      EXPECT_EQ(again.waypoint(p), plan[0]) << "at " << here.x << ", " << here.y;
      return;
    }
  }
  ADD_FAILURE() << "no spot without a sight line farther out";
}

TEST(GridPlanner, NoPathWhenEnclosedOrTheGoalIsBlockedAndEscapesAFromAStartInTheInflation)
{
  cv::Mat1b cells(50, 50, uchar(0));
  cv::rectangle(cells, cv::Rect(20, 20, 10, 10), 100, 1);  // a closed box around (2.5, 2.5)
  const OccupancyMap boxed(cells, 0, 0, 0.1);
  GridPlanner::Options o;
  o.radius = 0.05;
  EXPECT_TRUE(GridPlanner::plan(boxed, {0.5, 0.5}, {2.5, 2.5}, o).empty());
  EXPECT_TRUE(GridPlanner::plan(boxed, {0.5, 0.5}, {2.05, 2.5}, o).empty());  // on the wall
  EXPECT_TRUE(GridPlanner::plan(boxed, {0.5, 0.5}, {9.0, 0.5}, o).empty());   // outside the map
  o.radius = 0.4;
  EXPECT_FALSE(GridPlanner::plan(boxed, {1.85, 1.0}, {0.5, 4.5}, o).empty());  // starts 0.15 m from the box
  // Unknown cells are free.
  cv::Mat1b unknown(50, 50, OccupancyMap::kUnknown);
  EXPECT_FALSE(GridPlanner::plan(OccupancyMap(unknown, 0, 0, 0.1), {0.5, 0.5}, {4.5, 4.5}, o).empty());
}

TEST(TaskSpec, ParsesMissionsAndRefusesBadOnesNamingTheProblem)
{
  const auto tasks = TaskSpec::parseYaml(
      "mission: find_and_return\n"
      "tasks:\n"
      "  - {task: search, object: target_box, timeout: 240, on_failure: continue}\n"
      "  - type: sequence\n"
      "    steps:\n"
      "      - {type: turn, angle: 3.14}\n"
      "      - {type: return_home}\n");
  ASSERT_EQ(tasks.size(), 2u);
  EXPECT_EQ(tasks[0].object, "target_box");
  EXPECT_EQ(tasks[0].timeout, 240);
  EXPECT_EQ(tasks[1].steps.size(), 2u);
  EXPECT_EQ(tasks[1].steps[1].type, "return_home");

  auto error = [](const std::string& yaml) {
    try
    {
      TaskSpec::parseYaml(yaml, "m.yaml");
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("tasks:\n  - {type: fly}\n").substr(0, 9), "m.yaml:2:");
  EXPECT_NE(error("tasks:\n  - {type: fly}\n").find("unknown task type 'fly'"), std::string::npos);
  EXPECT_NE(error("tasks:\n  - {type: search}\n").find("search needs an object"), std::string::npos);
  EXPECT_NE(error("tasks:\n  - {type: wait, speed: 3}\n").find("unknown key 'speed'"), std::string::npos);
  EXPECT_NE(error("tasks:\n  - {type: wait, duration: fast}\n").find("'duration'"), std::string::npos);
  EXPECT_NE(error("tasks:\n  - {type: go_to, x: .nan, y: 0}\n").find("non-finite"), std::string::npos);
  EXPECT_NE(error("tasks: []\n").find("non-empty"), std::string::npos);

  const auto line = TaskSpec::parseText("search cup timeout=60 on_failure=return_home; go_to x=1.5 y=-2; stop");
  ASSERT_EQ(line.size(), 3u);
  EXPECT_EQ(line[0].on_failure, "return_home");
  EXPECT_TRUE(line[1].has_place);
  EXPECT_DOUBLE_EQ(line[1].y, -2);
  EXPECT_THROW(TaskSpec::parseText("search cup mug"), std::invalid_argument);
  EXPECT_THROW(TaskSpec::parseText(" ; "), std::invalid_argument);
}

TEST(SearchTask, ConcludesOnASecondSightingNearTheFirstNotOnASingleOne)
{
  const auto sighting = [](double x, double t) {
    Percept p = at(t);
    p.seen.push_back({"cup", x, 0.0, 0.9, t});
    return p;
  };
  TaskManager m;
  m.add(spec("search cup"));
  m.step(sighting(2.0, 0.0));  // one recognition: not yet
  EXPECT_FALSE(m.idle());
  m.step(sighting(6.0, 1.0));  // a second one 4 m away: a new candidate, no confirmation
  m.step(at(2.0));
  EXPECT_FALSE(m.idle());
  m.step(sighting(6.3, 12.0));  // too late for the candidate of t = 1 (confirm_time 10 s)
  EXPECT_FALSE(m.idle());
  m.step(sighting(6.2, 13.0));  // within 2 m and 10 s of the last: found
  EXPECT_TRUE(m.idle());
  ASSERT_EQ(m.finished().size(), 1u);
  EXPECT_EQ(m.finished()[0].state, TaskState::Succeeded);
  EXPECT_DOUBLE_EQ(m.record().found.at("cup").x, 6.2);
  // confirm_distance 0: the first sighting concludes, as before.
  TaskParameters once;
  once.confirm_distance = 0.0;
  TaskManager m2(once);
  m2.add(spec("search cup"));
  m2.step(sighting(2.0, 0.0));
  EXPECT_TRUE(m2.idle());
}

TEST(SearchTask, GoesFirstWhereTheMemoryRemembersTheObject)
{
  TaskManager m;
  m.add(spec("search cup"));
  Percept p = at(0);
  p.remembered.push_back({"cup", 4.0, 0.0, 0.9, -100});
  const MotorCommand c = m.step(p);
  EXPECT_EQ(c.mode, "excursion");
  EXPECT_EQ(c.base, MotorCommand::Base::Goal);
  EXPECT_NEAR(c.goal_x, 4.0, 1e-9);
  EXPECT_EQ(c.head_mode, "explore");
  Percept weak = at(0);
  weak.remembered.push_back({"cup", 4.0, 0.0, 0.1, -100});  // too weak a memory: explore
  TaskManager m2;
  m2.add(spec("search cup"));
  EXPECT_EQ(m2.step(weak).mode, "exploration");
}

TEST(SearchTask, StopsAndLooksRoundAtEachExplorationGoalThenDrivesLookingAhead)
{
  TaskParameters parameters;
  ASSERT_GT(parameters.look_time, 0.0);
  TaskManager m(parameters);
  m.add(spec("search cup"));
  Percept p = at(0, -2.0, 0.0, 0.3);
  p.map = wallMap();
  m.step(p);  // the first cycle starts the task
  p.time = 0.1;
  MotorCommand c = m.step(p);
  EXPECT_EQ(c.mode, "exploration");
  EXPECT_EQ(c.base, MotorCommand::Base::Heading);  // turning in place, a quarter turn ahead...
  EXPECT_NEAR(std::remainder(c.heading - (0.3 + M_PI / 2), 2 * M_PI), 0.0, 1e-9);
  EXPECT_EQ(c.head_mode, "explore");  // ...while the head explores
  p.time = 0.1 + parameters.look_time + 0.2;
  c = m.step(p);
  EXPECT_EQ(c.base, MotorCommand::Base::Goal);  // then it drives to the goal, looking where it goes
  EXPECT_EQ(c.head_mode, "look_ahead");
  // look_time 0: the thesis's way, the head explores while the base drives.
  parameters.look_time = 0.0;
  TaskManager thesis(parameters);
  thesis.add(spec("search cup"));
  p.time = 0;
  thesis.step(p);
  p.time = 0.1;
  c = thesis.step(p);
  EXPECT_EQ(c.base, MotorCommand::Base::Goal);
  EXPECT_EQ(c.head_mode, "explore");
}

// The thesis' mission on a kinematic point robot that drives to each Goal at 0.5 m/s: search an object
// behind a wall (seen within 2 m), then return home; exploration must find it, the return must plan
// around the wall the map holds.
TEST(TaskManager, FindAndReturnOnAPointRobot)
{
  TaskManager m;
  for (const auto& t : TaskSpec::parseText("search box timeout=600; return_home timeout=300"))
    m.add(t);
  const OccupancyMap map = wallMap();
  const cv::Point2d box(3.0, 0.5);
  double x = 0, y = 0, yaw = 0;
  bool returned = false;
  double blocked_since = -1;
  for (double t = 0; t < 900 && !returned; t += 0.2)
  {
    Percept p = at(t, x, y, yaw);
    p.map = map;
    p.base_trapped = blocked_since >= 0 && t - blocked_since > 3.0;  // the base controller's trap detector
    if (std::hypot(box.x - x, box.y - y) < 2.0)
      p.seen.push_back({"box", box.x, box.y, 0.9, t});
    const MotorCommand c = m.step(p);
    if (c.base == MotorCommand::Base::Goal)
    {
      const double dx = c.goal_x - x, dy = c.goal_y - y, d = std::hypot(dx, dy);
      const double s = std::min(d, 0.1);
      // The point robot refuses to enter the wall (the base's STM would stop it).
      const double nx = x + (d > 0 ? dx / d * s : 0), ny = y + (d > 0 ? dy / d * s : 0);
      if (!(nx > 0.8 && nx < 1.4 && std::abs(ny) < 3.2) && std::abs(nx) < 4.6 && std::abs(ny) < 4.6)
      {
        x = nx;
        y = ny;
        blocked_since = -1;
      }
      else if (blocked_since < 0)
        blocked_since = t;
      yaw = std::atan2(dy, dx);
    }
    else if (c.base == MotorCommand::Base::Heading)
      yaw = c.heading;
    returned = m.idle();
  }
  ASSERT_TRUE(returned);
  ASSERT_EQ(m.finished().size(), 2u);
  EXPECT_EQ(m.finished()[0].state, TaskState::Succeeded) << m.finished()[0].reason;
  EXPECT_EQ(m.finished()[1].state, TaskState::Succeeded) << m.finished()[1].reason;
  EXPECT_LT(std::hypot(x, y), 0.3);
  EXPECT_NEAR(m.record().found.at("box").x, 3.0, 1e-9);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

namespace
{
Percept withAction(Percept p, const std::string& action, double when)
{
  p.gesture_action = action;
  p.gesture_action_time = when;
  return p;
}
}  // namespace

TEST(GreetTask, AsksForAGreetingWithTheBaseStillAndSucceedsOnAnActionThatCameAfterItsStart)
{
  TaskManager m;
  m.add(spec("greet timeout=20"));
  const MotorCommand c = m.step(withAction(at(10), "stop", 5.0));  // an old action: not this greeting's
  EXPECT_TRUE(c.greet);
  EXPECT_EQ(c.base, MotorCommand::Base::Stop);
  EXPECT_EQ(c.head_mode, "");  // the HRI behaviour holds the head
  EXPECT_FALSE(m.idle());
  m.step(withAction(at(12), "continue", 11.5));
  EXPECT_TRUE(m.idle());
  EXPECT_EQ(m.finished().back().state, TaskState::Succeeded);
  EXPECT_EQ(m.finished().back().reason, "gesture action 'continue': the interrupted tasks go on");
  EXPECT_FALSE(m.step(at(13)).greet);
}

TEST(GreetTask, FailsAtItsTimeOutSayingWhyAndTheDefaultTimeOutIsTheParameter)
{
  TaskParameters p;
  p.greet_timeout = 7;
  TaskManager m(p);
  m.add(spec("greet"));
  m.step(at(0));
  m.step(at(6.9));
  EXPECT_FALSE(m.idle());
  m.step(at(7.1));
  ASSERT_TRUE(m.idle());
  EXPECT_EQ(m.finished().back().state, TaskState::Failed);
  EXPECT_EQ(m.finished().back().reason, "no gesture read in 7 s (nobody there, no face found or no known gesture)");
}

TEST(TaskManager, AGestureActionThatIsATaskReplacesThePlanAndOthersLetItGoOn)
{
  {  // return_home replaces the rest of the mission
    TaskManager m;
    m.add(spec("go_to x=4 y=0"));
    m.add(spec("greet priority=1"));
    m.add(spec("wait duration=100"));
    m.step(at(0, 0, 0));
    m.step(withAction(at(1, 2, 0), "return_home", 0.9));
    EXPECT_EQ(m.status().macro_task, "return_home");
    const MotorCommand c = m.step(at(1.2, 2, 0));
    EXPECT_EQ(c.base, MotorCommand::Base::Goal);
    EXPECT_NEAR(c.goal_x, 0.0, 1e-9);
    ASSERT_GE(m.finished().size(), 3u);
    EXPECT_EQ(m.finished()[0].name, "greet");
    EXPECT_EQ(m.finished()[0].reason, "gesture action 'return_home' replaces the plan");
    EXPECT_EQ(m.finished()[1].state, TaskState::Cancelled);
    EXPECT_EQ(m.finished()[1].reason, "replaced by the gesture action 'return_home'");
  }
  {  // stop: nothing is left, the base stands
    TaskManager m;
    m.add(spec("go_to x=4 y=0"));
    m.add(spec("greet priority=1"));
    m.step(at(0));
    EXPECT_EQ(m.step(withAction(at(1), "stop", 0.5)).base, MotorCommand::Base::Stop);
    EXPECT_TRUE(m.idle());
    EXPECT_EQ(m.finished().back().state, TaskState::Succeeded);  // the stop task itself
  }
  {  // follow is no task here: the interrupted go_to resumes
    TaskManager m;
    m.add(spec("go_to x=4 y=0"));
    m.add(spec("greet priority=1"));
    m.step(at(0));
    const MotorCommand c = m.step(withAction(at(1), "follow", 0.5));
    EXPECT_EQ(m.finished().back().reason,
              "gesture action 'follow' is no task the manager runs: the interrupted tasks go on");
    EXPECT_EQ(c.base, MotorCommand::Base::Goal);
    EXPECT_NEAR(c.goal_x, 4.0, 1e-9);
  }
}

TEST(TaskManager, AnObstacleInFrontWhileDrivingStartsOneGreetThenTheCooldownHoldsTheNext)
{
  // The wall of wallMap() runs along x = 1.0-1.2; the robot drives towards it along y = 0.
  TaskParameters p;
  p.greet_distance = 0.8;
  p.greet_cooldown = 30;
  p.greet_timeout = 5;
  TaskManager m(p);
  m.add(spec("go_to x=4 y=0"));
  auto near = [&](double t, double x, double yaw) {
    Percept q = at(t, x, 0, yaw);
    q.map = wallMap();
    return q;
  };
  EXPECT_EQ(m.step(near(0, -2, 0)).base, MotorCommand::Base::Goal);  // 3 m away: drives
  EXPECT_FALSE(m.step(near(1, -2, 0)).greet);
  const MotorCommand c = m.step(near(2, 0.5, 0));  // 0.5 m before the wall, facing it
  EXPECT_EQ(m.status().macro_task, "greet (obstacle in front)");
  EXPECT_TRUE(c.greet);
  EXPECT_EQ(c.base, MotorCommand::Base::Stop);
  m.step(near(8, 0.5, 0));  // nobody answered: the greet fails, the go_to resumes ...
  EXPECT_EQ(m.finished().back().state, TaskState::Failed);
  const MotorCommand resumed = m.step(near(8.2, 0.5, 0));
  EXPECT_EQ(m.status().macro_task, "go_to (4, 0)");
  EXPECT_FALSE(resumed.greet);
  m.step(near(20, 0.5, 0));  // ... and the same wall starts no greet within the cooldown
  EXPECT_EQ(m.status().macro_task, "go_to (4, 0)");
  m.step(near(39, 0.5, 0));  // after it, it does
  EXPECT_EQ(m.status().macro_task, "greet (obstacle in front)");

  TaskManager sideways(p);  // the wall beside the robot is not in front
  sideways.add(spec("go_to x=4 y=0"));
  sideways.step(near(0, 0.5, M_PI / 2));
  sideways.step(near(1, 0.5, M_PI / 2));
  EXPECT_NE(sideways.status().macro_task, "greet (obstacle in front)");

  TaskManager far(p);  // a pose far outside the map: nothing in front (and no int overflow on the way)
  far.add(spec("go_to x=4 y=0"));
  far.step(near(0, 1e20, 0));
  far.step(near(1, -1e20, 0));
  EXPECT_EQ(far.status().macro_task, "go_to (4, 0)");

  TaskManager off;  // greet_distance 0 (the default): never
  off.add(spec("go_to x=4 y=0"));
  off.step(near(0, 0.5, 0));
  off.step(near(1, 0.5, 0));
  EXPECT_EQ(off.status().macro_task, "go_to (4, 0)");
}
