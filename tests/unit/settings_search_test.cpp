// The search of `obscura tune` (samples/common/settings_search.h) on synthetic objectives with known optima:
// a bowl inside the box over two continuous coordinates and an integer one, an optimum on the box's boundary,
// an enumerated coordinate, a constraint (infeasible points, a start outside it), and the bookkeeping
// (evaluation budget, no point twice, the same history for the same seed). No GL, no SDK.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "settings_search.h"

namespace {

using obscura::samples::continuous_parameter;
using obscura::samples::coordinate_of_level;
using obscura::samples::enumerated_parameter;
using obscura::samples::Evaluation;
using obscura::samples::EvaluatedPoint;
using obscura::samples::integer_parameter;
using obscura::samples::level_of;
using obscura::samples::pattern_search;
using obscura::samples::SearchOptions;
using obscura::samples::SearchParameter;
using obscura::samples::SearchResult;

double square(double x) { return x * x; }

SearchOptions with_budget(int evaluations, uint64_t seed = 1) {
    SearchOptions options;
    options.max_evaluations = evaluations;
    options.seed = seed;
    return options;
}

// A quadratic bowl, minimum 0 at (0.3, 0.7) and integer level 6 of 0..10, inside the box; the start is far from
// it in every coordinate. Within 60 evaluations the search comes within 0.02 of it in each continuous coordinate
// and finds the integer level exactly.
TEST(SettingsSearch, FindsTheMinimumOfABowlInsideTheBox) {
    const std::vector<SearchParameter> parameters = {continuous_parameter(), continuous_parameter(),
                                                     integer_parameter(11)};
    const auto bowl = [](const std::vector<double>& x) {
        const double level = x[2] * 10.0;
        return Evaluation{square(x[0] - 0.3) + 2.0 * square(x[1] - 0.7) + 0.01 * square(level - 6.0), 0.0};
    };
    const SearchResult result = pattern_search(parameters, {0.95, 0.05, 0.0}, bowl, with_budget(60));
    ASSERT_TRUE(result.best.feasible());
    EXPECT_LE(result.history.size(), 60u);
    EXPECT_NEAR(result.best_point[0], 0.3, 0.02);
    EXPECT_NEAR(result.best_point[1], 0.7, 0.02);
    EXPECT_EQ(level_of(parameters[2], result.best_point[2]), 6);
    EXPECT_LT(result.best.value, 1e-3);
    // The start is the first evaluation, and the best is the one the history marks last.
    EXPECT_EQ(result.history.front().point, obscura::samples::snap_point(parameters, {0.95, 0.05, 0.0}));
    const auto last_best = std::find_if(result.history.rbegin(), result.history.rend(),
                                        [](const EvaluatedPoint& point) { return point.best; });
    ASSERT_NE(last_best, result.history.rend());
    EXPECT_EQ(last_best->index, result.best_index);
    EXPECT_EQ(result.history[size_t(result.best_index)].point, result.best_point);
}

// The unconstrained minimum (1.4, -0.3) lies outside the box: the best point is the box's corner (1, 0), exactly
// (the steps are clamped to the box), within 40 evaluations.
TEST(SettingsSearch, FindsAnOptimumOnTheBoundaryExactly) {
    const std::vector<SearchParameter> parameters = {continuous_parameter(), continuous_parameter()};
    const auto outside = [](const std::vector<double>& x) {
        return Evaluation{square(x[0] - 1.4) + square(x[1] + 0.3), 0.0};
    };
    const SearchResult result = pattern_search(parameters, {0.4, 0.6}, outside, with_budget(40));
    EXPECT_LE(result.history.size(), 40u);
    EXPECT_EQ(result.best_point[0], 1.0);
    EXPECT_EQ(result.best_point[1], 0.0);
    EXPECT_NEAR(result.best.value, square(0.4) + square(0.3), 1e-12);
}

// An enumerated coordinate of four unordered levels whose costs are not monotonic in the level (3, 1, 4, 0.5 for
// levels 0..3: a compass step from level 0 would stop at 1), beside a continuous one: the search tries every
// other level and finds level 3 and the continuous minimum at 0.25.
TEST(SettingsSearch, FindsTheBestLevelOfAnEnumeratedParameter) {
    const std::vector<SearchParameter> parameters = {enumerated_parameter(4), continuous_parameter()};
    const double level_cost[4] = {3.0, 1.0, 4.0, 0.5};
    const auto objective = [&](const std::vector<double>& x) {
        return Evaluation{level_cost[level_of(parameters[0], x[0])] + square(x[1] - 0.25), 0.0};
    };
    const SearchResult result = pattern_search(parameters, {0.0, 0.9}, objective, with_budget(40));
    EXPECT_EQ(level_of(parameters[0], result.best_point[0]), 3);
    EXPECT_NEAR(result.best_point[1], 0.25, 0.02);
    // Enumerated coordinates are only ever evaluated at their levels.
    for (const EvaluatedPoint& point : result.history) {
        EXPECT_EQ(point.point[0], coordinate_of_level(parameters[0], level_of(parameters[0], point.point[0])));
    }
}

// A budget: points with x0 + x1 > 0.8 are infeasible (violation: how far over), and the bowl's minimum (0.7,
// 0.7) is outside it; the constrained minimum is (0.4, 0.4), value 0.18, on the constraint's edge, which runs
// diagonally to the coordinates (where a compass search is slow: it can only slide along the edge by random
// directions). The start is itself over the budget: for every seed from 1 to 10, within 80 evaluations, the
// search walks into the feasible set and ends within 0.04 of the constrained minimum's value, and once it has
// seen a feasible point no infeasible one is ever the best.
TEST(SettingsSearch, RespectsAConstraintAndStartsOutsideIt) {
    const std::vector<SearchParameter> parameters = {continuous_parameter(), continuous_parameter()};
    const auto objective = [](const std::vector<double>& x) {
        return Evaluation{square(x[0] - 0.7) + square(x[1] - 0.7), x[0] + x[1] - 0.8};
    };
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        const SearchResult result = pattern_search(parameters, {0.9, 0.95}, objective, with_budget(80, seed));
        EXPECT_FALSE(result.history.front().evaluation.feasible());
        ASSERT_TRUE(result.best.feasible()) << "seed " << seed;
        EXPECT_LE(result.best_point[0] + result.best_point[1], 0.8) << "seed " << seed;
        EXPECT_LE(result.best.value, 0.18 + 0.04) << "seed " << seed;
        bool seen_feasible = false;
        for (const EvaluatedPoint& point : result.history) {
            if (seen_feasible && point.best) {
                EXPECT_TRUE(point.evaluation.feasible());
            }
            seen_feasible = seen_feasible || point.evaluation.feasible();
        }
    }
}

// Points the objective cannot evaluate at all (violation +infinity, or a NaN value: settings the SDK refuses)
// are never the best, and the search goes on around them.
TEST(SettingsSearch, NeverPicksPointsThatCannotBeEvaluated) {
    const std::vector<SearchParameter> parameters = {integer_parameter(9)};
    const auto objective = [&](const std::vector<double>& x) {
        const int level = level_of(parameters[0], x[0]);
        if (level % 2 == 1) return Evaluation{std::numeric_limits<double>::quiet_NaN(), 0.0};  // odd: refused
        if (level == 6) return Evaluation{0.0, std::numeric_limits<double>::infinity()};
        return Evaluation{square(double(level) - 5.5), 0.0};
    };
    const SearchResult result = pattern_search(parameters, {0.0}, objective, with_budget(9));
    EXPECT_EQ(level_of(parameters[0], result.best_point[0]), 4);
    EXPECT_TRUE(result.best.feasible());
}

// The budget counts objective calls, the start included; no point is evaluated twice; the same seed gives the
// same calls in the same order, another seed (with restarts) other calls.
TEST(SettingsSearch, KeepsTheBudgetAndIsDeterministic) {
    const std::vector<SearchParameter> parameters = {continuous_parameter(), integer_parameter(5),
                                                     enumerated_parameter(3)};
    std::vector<std::vector<double>> calls;
    const auto objective = [&](const std::vector<double>& x) {
        calls.push_back(x);
        return Evaluation{std::sin(7.0 * x[0]) + x[1] + (x[2] == 0.5 ? -0.2 : 0.0), 0.0};
    };
    for (int budget : {1, 7, 25}) {
        calls.clear();
        const SearchResult result = pattern_search(parameters, {0.5, 0.5, 0.0}, objective, with_budget(budget));
        EXPECT_LE(int(result.history.size()), budget);
        EXPECT_EQ(calls.size(), result.history.size());
        EXPECT_EQ(std::set<std::vector<double>>(calls.begin(), calls.end()).size(), calls.size()) << budget;
    }
    // A coarse mesh converges long before 40 calls: the rest are restarts, from points the seed draws.
    SearchOptions options = with_budget(40, 7);
    options.min_step = 1.0 / 16.0;
    calls.clear();
    const SearchResult first = pattern_search(parameters, {0.5, 0.5, 0.0}, objective, options);
    const std::vector<std::vector<double>> first_calls = calls;
    calls.clear();
    const SearchResult second = pattern_search(parameters, {0.5, 0.5, 0.0}, objective, options);
    EXPECT_EQ(calls, first_calls);
    EXPECT_EQ(first.best_point, second.best_point);
    EXPECT_GE(first.restarts, 1);
    calls.clear();
    options.seed = 8;
    pattern_search(parameters, {0.5, 0.5, 0.0}, objective, options);
    EXPECT_NE(calls, first_calls);
}

// A box with nothing to try (one level) converges at once and stops: one call, no endless restarts.
TEST(SettingsSearch, StopsWhenNothingIsLeftToTry) {
    const std::vector<SearchParameter> parameters = {integer_parameter(1), enumerated_parameter(1)};
    int calls = 0;
    const SearchResult result = pattern_search(
        parameters, {0.3, 0.9},
        [&](const std::vector<double>&) {
            ++calls;
            return Evaluation{1.0, 0.0};
        },
        with_budget(50));
    EXPECT_EQ(calls, 1);
    EXPECT_TRUE(result.converged);
    EXPECT_EQ(result.best_point, (std::vector<double>{0.0, 0.0}));
}

// Gains below min_improvement do not move the search: a slope of 1e-7 per unit leaves the start the best, while
// a coordinate that gains 0.01 still moves.
TEST(SettingsSearch, IgnoresImprovementsBelowTheMargin) {
    const std::vector<SearchParameter> parameters = {continuous_parameter(), continuous_parameter()};
    const auto objective = [](const std::vector<double>& x) { return Evaluation{-1e-7 * x[0] - 0.01 * x[1], 0.0}; };
    SearchOptions options = with_budget(30);
    options.min_improvement = 1e-5;
    const SearchResult result = pattern_search(parameters, {0.5, 0.5}, objective, options);
    EXPECT_EQ(result.best_point[0], 0.5);
    EXPECT_EQ(result.best_point[1], 1.0);
}

// A parameter's scale sets its steps: the first poll moves the coordinate by initial_step x scale (a log range of
// many decades starts with a factor of 2, not a quarter of the box), an integer one by as many levels.
TEST(SettingsSearch, ScalesTheStepsOfAParameter) {
    for (const SearchParameter& parameter : {continuous_parameter(0.1), integer_parameter(101, 0.2)}) {
        std::vector<double> calls;
        const auto objective = [&](const std::vector<double>& x) {
            calls.push_back(x[0]);
            return Evaluation{std::fabs(x[0] - 0.5), 0.0};
        };
        pattern_search({parameter}, {0.5}, objective, with_budget(2));
        ASSERT_EQ(calls.size(), 2u);
        EXPECT_NEAR(std::fabs(calls[1] - calls[0]), 0.25 * parameter.scale, 1e-9);
    }
}

TEST(SettingsSearch, RefusesWrongArguments) {
    const auto objective = [](const std::vector<double>&) { return Evaluation{0.0, 0.0}; };
    EXPECT_THROW(pattern_search({}, {}, objective, with_budget(5)), std::invalid_argument);
    EXPECT_THROW(pattern_search({continuous_parameter()}, {0.1, 0.2}, objective, with_budget(5)),
                 std::invalid_argument);
    EXPECT_THROW(pattern_search({integer_parameter(0)}, {0.0}, objective, with_budget(5)), std::invalid_argument);
    EXPECT_THROW(pattern_search({continuous_parameter(0.0)}, {0.0}, objective, with_budget(5)), std::invalid_argument);
    EXPECT_THROW(pattern_search({continuous_parameter()}, {0.1}, objective, with_budget(0)), std::invalid_argument);
    SearchOptions options = with_budget(5);
    options.min_step = 0.5;
    EXPECT_THROW(pattern_search({continuous_parameter()}, {0.1}, objective, options), std::invalid_argument);
}

}  // namespace
