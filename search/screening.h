// disco — a screened search (search.screen_fraction > 0; search/README.md, "Screening"):
// every start first runs on its scene at fewer steps (the screen), and only the best screened
// starts of each scene run at the scene's own N_t, from their screened answer (the refine).
//
//   screen   start k's objective reduction (its own guess and schedule) on the scene at
//            screen_steps() steps. Its answer is recorded (runs.jsonl, stage "screen"; its
//            solution file in DIR/screened/SCENE/K.json) and never counts as the scene's
//            result: a screened T_f is that of a coarser model.
//   refine   once every screen of a scene has an outcome (or, under a time limit, once the
//            screening share of it is used), refine_choice() picks up to refine_count
//            screened starts; each runs at full N_t from its screened answer resampled to N_t
//            (a start of kind kGiven, as with --guess: search/trajectory.h), keeping the
//            start's own schedule; or, with search.refine_from "start", from the start's own
//            guess, as a search without screening runs it; or, with "both", the first and then
//            the second, keeping the better. Its outcome is the start's (stage "refine"): the
//            scene's best is always a refined, full-N_t, certified answer.
//   fill     under a time limit (the search's or the scene's own), the limit and not
//            refine_count ends the refines: once the chosen ones are handed out, a rank that
//            would idle refines the next screen of refine_choice's ranking of all the
//            scene's screens, and once those are refined, runs the starts without a certified
//            screen (never screened, or not certified) at full N_t from their own guess, in
//            the queue's order (time_left_order; search/coordinator.h, add_fill_refine).
//   early    with search.early_refine_batch B > 0, refines also start while the scene is
//            still screening (early_refine_choice): after every batch of B screens (starts
//            0..B−1, B..2B−1, ...) has ended, the batch's best screen is refined at once if
//            it is below every earlier batch's best. Under a time limit the screening share
//            otherwise leaves the refines to its second part; the first good refine can
//            then come a few screens into the search.
//
// The choice depends only on the screens' outcomes, so a screened search keeps the
// guarantees of the deterministic mode (the same runs and best on 1 or 2 ranks, and after
// --resume).
#pragma once

#include <string>
#include <vector>

#include "core/model/scene.h"
#include "core/config/settings.h"

namespace disco {

// search.screen_fraction, search.refine_count, search.screen_share of the settings.
// Where a refine starts (search.refine_from): kScreen, from the start's screened answer
// resampled to N_t (as with --guess); kStart, from the start's own guess with its whole
// objective reduction, as the start runs in a search without screening (the screen then only
// chooses which starts run at full N_t, and in what order); kBoth, from the screen and then,
// in the budget left, from the start, the refine's outcome being the better of the two (the
// two land in different local optima: search/README.md, "Screening").
enum class RefineFrom { kScreen, kStart, kBoth };

struct ScreenSettings {
  double fraction = 0.0;  // 0: no screening (every start at full N_t, as without stages)
  int refine_count = 0;   // refines per scene, at most
  double share = 0.0;     // under a time limit: the share of it screens may use
  int early_batch = 0;    // search.early_refine_batch: screens per batch (0: no early refines)
  RefineFrom refine_from = RefineFrom::kScreen;  // search.refine_from
  double tie = 0.0;       // search.screen_tie: screens this close (relative) rank by start
  // search.refine_minimize_weak: a refine chosen from its certified screen runs the weak attempt
  // of its minimisations as the relaxation homotopy (true) or the penalty loop (false), whatever
  // reduction.minimize_weak says: its run from the screened answer and, with refine_from both,
  // its run from the start's own guess. A refine from the start alone (refine_from start) and a
  // start run in the time left without a certified screen run as a search without screening
  // runs that start.
  bool refine_weak_homotopy = false;
  bool on() const { return fraction > 0.0; }
};
// InputError naming the key for a value out of its range.
ScreenSettings screen_settings(const Settings& settings);

// The steps a screen runs at: max(2, round(fraction · N_t)), at most N_t.
int screen_steps(const Scene& scene, double fraction);

// One screened start as the choice sees it.
struct Screened {
  int start = 0;
  double value = 0.0;     // its certified J (T_f for objective time); NaN: none
  std::string class_key;  // the homotopy class of its answer (search/homotopy.h), "" if none
};

// Whether screened value a is below b by more than the relative tie (search.screen_tie):
// b − a > tie·max(|a|, |b|). Screens within the tie of each other are taken as one local optimum
// of the coarse model, their order as roundoff: they rank by start index, the order a search
// without screening runs them in, and not by digits the solver does not resolve.
bool screen_below(double a, double b, double tie);

// The starts to refine, in the order they should run. The certified screens are ranked by value
// in groups: a group opens at the lowest value not yet grouped and holds every value v within
// the tie above it (!screen_below(first, v, tie)); within a group, by start. From that ranking: first the best of each homotopy class (a class "" counts
// as its own each time), then the next best not yet chosen, until `count` are chosen or none is
// left.
std::vector<int> refine_choice(std::vector<Screened> screened, int count, double tie);

// The order in which the time left of a limit runs a scene's starts once its chosen refines are
// handed out (search/README.md, "Screening", step 5): first refine_choice's ranking of every
// certified screen in `screened`; then the starts without a certified screen, which run at full
// N_t from their own guess as a search without screening runs them: those never screened (no
// entry in `screened`) before those whose screen ended without a certified point, each group in
// `hand_out_order` (the queue's order of the scene's starts, search/task_queue.h).
std::vector<int> time_left_order(const std::vector<Screened>& screened, const std::vector<int>& hand_out_order,
                                 double tie);

// The early refines of a scene of `starts` starts, in the order they are decided, from its
// screens with a final outcome (`ended`; value NaN: not certified). Batch b holds the screens of
// starts b·batch .. min((b+1)·batch, starts)−1. Batches are decided in order, each once all of
// its screens and the earlier batches' have ended: its best certified screen (scanned by start,
// a screen replaces the one held only if screen_below it) is chosen if it is screen_below the
// best certified screen of every earlier batch (a batch without one chooses nothing). The first batch with a screen not yet ended stops the
// decisions, so the answer depends only on the screens' outcomes, never on when they ended.
std::vector<int> early_refine_choice(const std::vector<Screened>& ended, int starts, int batch, double tie);

}  // namespace disco
