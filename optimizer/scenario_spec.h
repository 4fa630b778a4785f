// A lighting state of an installation beside its normal one (issue 38): which of its
// luminaires are lit and at what fraction of the flux the search gave them, whether the
// light counted is all of it or only what comes straight from the sources, and the goal
// lines judged in that state. A scene of a control system, an emergency state (direct
// light only) or a design sky are each one: evaluated through the same operator columns
// as the search (T's candidate columns, or their direct part) and verified on the same
// verification (the exact solve's rows, or the sample operator), never by a pipeline of
// their own (job/scenario.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/base/error.h"
#include "optimizer/goal_spec.h"

namespace ilp {

// Which luminaires of a group a level takes: all, or every other one counted from the
// first (odd: the 1st, 3rd, ... as named L1, L3, ...; even: the 2nd, 4th, ...).
enum class ScenarioPick { all, odd, even };
inline std::string_view scenario_pick_key(ScenarioPick p) {
  constexpr std::string_view keys[] = {"all", "odd", "even"};
  return keys[static_cast<int>(p)];
}

struct ScenarioLevel {
  std::string group;  // a luminaire group's name; empty: every luminaire of the layout
  ScenarioPick pick = ScenarioPick::all;
  double fraction = 1.0;  // of the luminaire's flux, in [0, 1]
};

struct ScenarioSpec {
  std::string name;
  LightCounted light = LightCounted::total;
  double fraction = 1.0;              // every layout luminaire's, before the levels
  std::vector<ScenarioLevel> levels;  // applied in order, each over the ones before
  double fixed_fraction = 1.0;        // the job's placed luminaires and emitting surfaces
  std::vector<GoalSpec> goals;        // each names a goal area of the model; initial targets in a plan
  FileLoc loc;
};

// Is luminaire `index` (0-based within its group) taken by `pick`?
inline bool scenario_picks(ScenarioPick pick, std::size_t index) {
  switch (pick) {
    case ScenarioPick::all: return true;
    case ScenarioPick::odd: return index % 2 == 0;
    case ScenarioPick::even: return index % 2 == 1;
  }
  return false;
}

}  // namespace ilp
