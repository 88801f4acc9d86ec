// A deterministic derivative-free search over a box of normalised parameters, for `obscura tune`: no GL, no
// SDK, so that it can be tested on synthetic objectives.
//
//     std::vector<SearchParameter> parameters = {continuous(), integer(11), enumerated(3)};
//     SearchOptions options;
//     options.max_evaluations = 60;
//     SearchResult result = pattern_search(parameters, start, [](const std::vector<double>& x) {
//         return Evaluation{error_of(x), cost_of(x) / budget - 1.0};  // violation > 0: over budget
//     }, options);
//
// Every coordinate lies in [0, 1]. A continuous one takes any value there; an integer one with L levels takes
// k / (L - 1) for k = 0 .. L - 1 (ordered: neighbouring levels are neighbouring values); an enumerated one the
// same coordinates, but its levels are unordered names (toggles, modes), so it is searched by trying every other
// level. The caller maps coordinates to values (linear or log ranges, value lists).
//
// The algorithm (a compass search with Hooke-Jeeves' pattern move, random poll directions and random restarts;
// Kolda, Lewis and Torczon, "Optimization by Direct Search", SIAM Review 2003, sec. 3):
//   1. Evaluate the start. The mesh size m starts at `initial_step`.
//   2. A sweep polls every coordinate once, in an order drawn from the seed: continuous ones at x +- m s (s the
//      parameter's scale; clamped to the box), integer ones at +- max(1, round(m s (L - 1))) levels, enumerated
//      ones at every other level. The first poll point that is better than the current point is taken
//      (opportunistic polling), and the sweep goes on from there with the next coordinate.
//   3. After a sweep that moved, the pattern point x + (x - x_before_the_sweep) is tried once.
//   4. After a sweep that did not move, `random_directions` random directions, each in the plane of two ordered
//      (continuous or integer) coordinates drawn at random, are polled both ways at the mesh size (the compass
//      directions alone stall where a constraint runs diagonally to them: a budget two settings spend together);
//      the first better point is taken and the sweeps go on. When none is better, m is halved; when it would
//      fall below `min_step` the local search has converged, and if evaluations are left it restarts from a
//      point drawn uniformly from the box (seeded).
//   5. Points are snapped (integer and enumerated coordinates to their levels) before they are evaluated, and no
//      snapped point is evaluated twice: the budget counts distinct objective calls only.
// "Better" follows the feasibility rules of constrained direct search: a feasible point (violation <= 0 and a
// finite value) beats an infeasible one; two feasible points compare by value (lower by more than
// `min_improvement`), two infeasible ones by violation. So a search that starts over budget walks towards the
// budget first.
//
// The result depends on nothing but the parameters, the start, the objective's values and the options: the
// random numbers are a splitmix64 sequence drawn from the seed, the same on every platform.
#ifndef OBSCURA_SAMPLES_SETTINGS_SEARCH_H
#define OBSCURA_SAMPLES_SETTINGS_SEARCH_H

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace obscura::samples {

enum class ParameterKind { Continuous, Integer, Enumerated };

struct SearchParameter {
    ParameterKind kind = ParameterKind::Continuous;
    int levels = 0;     // Integer and Enumerated: how many values (>= 1); ignored for Continuous
    double scale = 1.0; // Continuous and Integer: the coordinate's steps are the mesh size times this, in (0, 1]
                        // (a log range of many decades takes smaller steps than a linear one)
};

SearchParameter continuous_parameter(double scale = 1.0);
SearchParameter integer_parameter(int levels, double scale = 1.0);
SearchParameter enumerated_parameter(int levels);

// What the objective says about a point.
struct Evaluation {
    double value = std::numeric_limits<double>::infinity();  // to minimise
    double violation = 0.0;  // > 0: infeasible (how far over a constraint); +infinity: not evaluable at all
    // Feasible: violation <= 0 and a finite value.
    bool feasible() const;
};

// The feasibility rules above: whether `a` is better than `b`; two feasible points only when a's value is lower
// by more than `margin` (>= 0).
bool better(const Evaluation& a, const Evaluation& b, double margin = 0.0);

using Objective = std::function<Evaluation(const std::vector<double>& point)>;

struct EvaluatedPoint {
    std::vector<double> point;  // snapped
    Evaluation evaluation;
    int index = 0;     // 0-based order of the call
    int restart = 0;   // 0: the local search from the start, then 1, 2 ... for each restart
    bool best = false; // better than every point evaluated before it (the first point always is)
};

struct SearchOptions {
    int max_evaluations = 60;  // objective calls, the start included (>= 1)
    uint64_t seed = 1;
    double initial_step = 0.25;      // the first mesh size, as a fraction of the box (0, 1]
    double min_step = 1.0 / 128.0;   // the local search converges when the mesh would fall below it (0, initial]
    int random_directions = 2;       // random directions polled (both ways) before the mesh shrinks (>= 0)
    bool restarts = true;            // restart from random points while evaluations are left
    // A feasible point replaces a feasible one only when its value is lower by more than this (>= 0): moves that
    // gain less than what the objective can resolve would only wander off the start.
    double min_improvement = 0.0;
    // Called after each objective call (progress reports); may be empty.
    std::function<void(const EvaluatedPoint&)> on_evaluation;
};

struct SearchResult {
    std::vector<double> best_point;  // snapped; the start when nothing beat it
    Evaluation best;
    int best_index = 0;               // into history
    std::vector<EvaluatedPoint> history;  // every objective call, in order
    int restarts = 0;                 // restarts begun
    bool converged = false;           // the last local search reached min_step (rather than the budget)
};

// Snaps `point` into the box: continuous coordinates clamped to [0, 1] (NaN becomes 0), integer and enumerated
// ones to the nearest level's coordinate. std::invalid_argument when the sizes differ.
std::vector<double> snap_point(const std::vector<SearchParameter>& parameters, const std::vector<double>& point);
// The level (0 .. levels - 1) of an integer or enumerated coordinate, and the coordinate of a level.
int level_of(const SearchParameter& parameter, double coordinate);
double coordinate_of_level(const SearchParameter& parameter, int level);

// The search described at the top of the file, from `start` (snapped first). std::invalid_argument for no
// parameters, a start of another size, a parameter with fewer than 1 level or a scale outside (0, 1], or options
// out of their ranges.
// Exceptions thrown by the objective propagate.
SearchResult pattern_search(const std::vector<SearchParameter>& parameters, const std::vector<double>& start,
                            const Objective& objective, const SearchOptions& options);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_SETTINGS_SEARCH_H
