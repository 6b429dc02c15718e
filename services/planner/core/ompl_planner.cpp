// OMPL glue: state space, validity and motion checks on the grid, planner choice, simplification.
#include "planner/core/ompl_planner.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>

#include "planner/core/line_of_sight.hpp"
#include "planner/core/ompl_planner_neighbors.hpp"

namespace slam::planner {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

Vec2 to_vec(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return Vec2{v->values[0], v->values[1]};
}

class GridValidityChecker : public ob::StateValidityChecker {
 public:
  GridValidityChecker(const ob::SpaceInformationPtr& si, const PlanningGrid& grid, UnknownPolicy policy)
      : ob::StateValidityChecker(si), grid_(grid), policy_(policy) {}

  bool isValid(const ob::State* state) const override {
    const auto cell = grid_.cell_at(to_vec(state));
    return cell && !grid_.impassable(*cell, policy_);
  }

 private:
  const PlanningGrid& grid_;
  UnknownPolicy policy_;
};

// Checks a motion by walking every cell the segment touches, so no path clips an obstacle corner.
class GridMotionValidator : public ob::MotionValidator {
 public:
  GridMotionValidator(const ob::SpaceInformationPtr& si, const PlanningGrid& grid, UnknownPolicy policy)
      : ob::MotionValidator(si), grid_(grid), policy_(policy) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool ok = segment_clear(grid_, to_vec(s1), to_vec(s2), policy_);
    count(ok);
    return ok;
  }

  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    const double hit = first_blocked_fraction(grid_, to_vec(s1), to_vec(s2), policy_);
    const bool ok = hit > 1.0;
    count(ok);
    if (!ok) {
      // Step back a little from the blocked cell's boundary so the reported state is valid.
      const double length = distance(to_vec(s1), to_vec(s2));
      const double back = length > 0.0 ? 1e-3 * grid_.resolution() / length : 0.0;
      last_valid.second = std::max(0.0, hit - back);
      if (last_valid.first != nullptr) {
        si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
      }
    }
    return ok;
  }

 private:
  void count(bool ok) const {
    // valid_/invalid_ are statistics in OMPL's base class; it declares them mutable.
    if (ok) {
      ++valid_;
    } else {
      ++invalid_;
    }
  }

  const PlanningGrid& grid_;
  UnknownPolicy policy_;
};

// FMT* (fast marching tree) with BucketNearestNeighbors in place of OMPL's default structure: FMT*
// samples all its states up front and asks each expanded state for its k nearest, which made the
// default GNAT's distance computations a third of the planning time (docs/performance.md, planner).
class BucketFmt : public og::FMT {
 public:
  BucketFmt(const ob::SpaceInformationPtr& si, uint32_t samples) : og::FMT(si) {
    setNumSamples(samples);
    // Each state links to fewer neighbours than OMPL's default (k = 0.8 of it): on the benchmark
    // map 8000 states at 0.8 gave shorter paths in less time than 6000 at 1.0 (docs/performance.md).
    setRadiusMultiplier(0.8);
    setName("FMTstar");
  }

  void setup() override {
    og::FMT::setup();
    const auto& bounds = si_->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds();
    const Vec2 origin{bounds.low[0], bounds.low[1]};
    const Vec2 extent{bounds.high[0] - bounds.low[0], bounds.high[1] - bounds.low[1]};
    // About four samples per bucket when they spread evenly: a k-nearest query reads a few rings.
    const double side = 2.0 * std::sqrt(extent.x * extent.y / std::max(1u, getNumSamples()));
    nn_ = std::make_shared<BucketNearestNeighbors<Motion*>>(
        origin, extent, side, [](Motion* const& m) { return to_vec(m->getState()); });
  }
};

ob::PlannerPtr make_planner(std::string_view name, const ob::SpaceInformationPtr& si, double range_m,
                            uint32_t fmt_samples) {
  if (name == "rrtconnect") {
    auto p = std::make_shared<og::RRTConnect>(si);
    if (range_m > 0.0) p->setRange(range_m);
    return p;
  }
  if (name == "rrtstar") {
    auto p = std::make_shared<og::RRTstar>(si);
    if (range_m > 0.0) p->setRange(range_m);
    return p;
  }
  if (name == "prmstar") return std::make_shared<og::PRMstar>(si);
  if (name == "fmtstar") return std::make_shared<BucketFmt>(si, fmt_samples);
  return nullptr;
}

}  // namespace

bool is_ompl_algorithm(std::string_view name) {
  return name == "rrtconnect" || name == "rrtstar" || name == "prmstar" || name == "fmtstar";
}

OmplPlanner::OmplPlanner(uint32_t seed, double range_m, uint32_t fmt_samples)
    : range_m_(range_m), fmt_samples_(fmt_samples) {
  static std::once_flag seeded;
  std::call_once(seeded, [seed] { ompl::RNG::setSeed(seed); });
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
}

OmplOutcome OmplPlanner::plan(const PlanningGrid& grid, Vec2 start, Vec2 goal, std::string_view algorithm,
                              double budget_s, UnknownPolicy policy) const {
  OmplOutcome outcome;
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  const GridGeometry& geo = grid.geometry();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, geo.origin.x);
  bounds.setLow(1, geo.origin.y);
  const Vec2 top_right = geo.corner(Cell{geo.width, geo.height});
  bounds.setHigh(0, top_right.x);
  bounds.setHigh(1, top_right.y);
  space->setBounds(bounds);

  og::SimpleSetup setup(space);
  const ob::SpaceInformationPtr& si = setup.getSpaceInformation();
  setup.setStateValidityChecker(std::make_shared<GridValidityChecker>(si, grid, policy));
  si->setMotionValidator(std::make_shared<GridMotionValidator>(si, grid, policy));
  setup.setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
  ob::PlannerPtr planner = make_planner(algorithm, si, range_m_, fmt_samples_);
  if (!planner) {
    outcome.status = PlanStatus::InvalidRequest;
    outcome.reason = "unknown OMPL algorithm '" + std::string(algorithm) + "'";
    return outcome;
  }
  setup.setPlanner(planner);

  ob::ScopedState<> from(space);
  ob::ScopedState<> to(space);
  from[0] = start.x;
  from[1] = start.y;
  to[0] = goal.x;
  to[1] = goal.y;
  setup.setStartAndGoalStates(from, to, 1e-6 * geo.resolution);
  setup.setup();

  const auto started = std::chrono::steady_clock::now();
  const ob::PlannerStatus solved = setup.solve(ob::timedPlannerTerminationCondition(0.75 * budget_s));
  if (solved != ob::PlannerStatus::EXACT_SOLUTION) {
    outcome.status = PlanStatus::Timeout;
    outcome.reason = std::string(algorithm) + " found no path within " + std::to_string(budget_s) + " s";
    return outcome;
  }
  og::PathGeometric& path = setup.getSolutionPath();
  const double used = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  og::PathSimplifier simplifier(si);
  if (algorithm == "fmtstar") {
    // FMT*'s path already takes near-shortest ways between obstacles: one pass of vertex removal
    // and shortcutting takes 0.1 ms; a full simplification took 5-30 ms on the benchmark map for
    // paths about 3 % shorter (docs/performance.md, planner).
    simplifier.reduceVertices(path);
    simplifier.shortcutPath(path);
  } else {
    simplifier.simplify(path, ob::timedPlannerTerminationCondition(std::max(0.0, budget_s - used)), true);
  }
  outcome.path.reserve(path.getStateCount());
  for (unsigned i = 0; i < path.getStateCount(); ++i) outcome.path.push_back(to_vec(path.getState(i)));
  outcome.status = PlanStatus::Ok;
  return outcome;
}

}  // namespace slam::planner
