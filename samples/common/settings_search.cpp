#include "settings_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace obscura::samples {
namespace {

// Continuous coordinates are kept on a grid of 2^-32, so that points reached along different paths (x + m - m)
// compare equal and are evaluated once.
constexpr double kGrid = 4294967296.0;

// After this many restarts in a row that evaluated nothing new, every point the search can reach has been seen
// (a small box of integer and enumerated levels): it stops rather than spin.
constexpr int kIdleRestartLimit = 8;

// splitmix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014): the same
// sequence on every platform, unlike the distributions of <random>.
class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    size_t below(size_t count) { return size_t(next() % uint64_t(count)); }
    template <class T>
    void shuffle(std::vector<T>& items) {
        for (size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[below(i)]);
    }

private:
    uint64_t state_;
};

Evaluation normalised(Evaluation evaluation) {
    if (std::isnan(evaluation.violation)) evaluation.violation = std::numeric_limits<double>::infinity();
    if (evaluation.violation <= 0.0 && !std::isfinite(evaluation.value)) {
        evaluation.violation = std::numeric_limits<double>::infinity();
    }
    return evaluation;
}

bool is_discrete(const SearchParameter& parameter) { return parameter.kind != ParameterKind::Continuous; }

class Search {
public:
    Search(const std::vector<SearchParameter>& parameters, const Objective& objective, const SearchOptions& options)
        : parameters_(parameters), objective_(objective), options_(options), random_(options.seed),
          last_direction_(parameters.size(), 0) {}

    SearchResult run(const std::vector<double>& start) {
        std::vector<double> x = snap_point(parameters_, start);
        std::optional<Evaluation> fx = evaluate(x);
        int idle_restarts = 0;
        while (fx) {
            const size_t before = result_.history.size();
            const bool converged = local_search(std::move(x), *fx);
            result_.converged = converged;
            if (!converged || !options_.restarts) break;
            idle_restarts = result_.history.size() == before ? idle_restarts + 1 : 0;
            if (idle_restarts >= kIdleRestartLimit) break;
            ++restart_;
            ++result_.restarts;
            x.assign(parameters_.size(), 0.0);
            for (double& coordinate : x) coordinate = random_.uniform();
            x = snap_point(parameters_, x);
            fx = evaluate(x);
        }
        return std::move(result_);
    }

private:
    // The objective's value at `point` (snapped), from the cache when it was evaluated before; nullopt once the
    // budget is spent and the point is new.
    std::optional<Evaluation> evaluate(const std::vector<double>& point) {
        const auto found = cache_.find(point);
        if (found != cache_.end()) return found->second;
        if (int(result_.history.size()) >= options_.max_evaluations) return std::nullopt;
        EvaluatedPoint evaluated;
        evaluated.point = point;
        evaluated.evaluation = normalised(objective_(point));
        evaluated.index = int(result_.history.size());
        evaluated.restart = restart_;
        evaluated.best =
            result_.history.empty() || better(evaluated.evaluation, result_.best, options_.min_improvement);
        if (evaluated.best) {
            result_.best = evaluated.evaluation;
            result_.best_point = point;
            result_.best_index = evaluated.index;
        }
        cache_.emplace(point, evaluated.evaluation);
        result_.history.push_back(evaluated);
        if (options_.on_evaluation) options_.on_evaluation(result_.history.back());
        return evaluated.evaluation;
    }

    // The poll points of coordinate `i` around `x` at mesh size `mesh`, in the order they are tried.
    std::vector<std::vector<double>> poll_points(const std::vector<double>& x, size_t i, double mesh) {
        const SearchParameter& parameter = parameters_[i];
        std::vector<std::vector<double>> points;
        if (parameter.kind == ParameterKind::Enumerated) {
            std::vector<int> levels;
            const int current = level_of(parameter, x[i]);
            for (int level = 0; level < parameter.levels; ++level) {
                if (level != current) levels.push_back(level);
            }
            random_.shuffle(levels);
            for (int level : levels) {
                points.push_back(x);
                points.back()[i] = coordinate_of_level(parameter, level);
            }
            return points;
        }
        const double step = step_of(parameter, mesh);
        if (step == 0.0) return points;
        // The direction that last improved this coordinate first; otherwise a random one.
        int first = last_direction_[i] != 0 ? last_direction_[i] : (random_.next() & 1u) ? 1 : -1;
        for (int direction : {first, -first}) {
            std::vector<double> point = x;
            point[i] += direction * step;
            point = snap_point(parameters_, point);
            if (point[i] != x[i]) points.push_back(std::move(point));
        }
        return points;
    }

    // The step of an ordered coordinate at mesh size `mesh`: integer ones at least one level.
    double step_of(const SearchParameter& parameter, double mesh) const {
        if (parameter.kind == ParameterKind::Continuous) return mesh * parameter.scale;
        if (parameter.kind == ParameterKind::Enumerated || parameter.levels < 2) return 0.0;
        const double spacing = 1.0 / double(parameter.levels - 1);
        return std::max(1.0, std::round(mesh * parameter.scale / spacing)) * spacing;
    }

    // x +- d for `random_directions` directions d in the plane of two ordered (continuous and integer)
    // coordinates drawn at random, each component uniform in [-1, 1], the larger scaled to the mesh; none when
    // fewer than two coordinates are ordered (the compass already covers one). Two at a time: a direction over
    // every coordinate at once is almost never a descent direction when a few of them dominate the objective.
    std::vector<std::vector<double>> random_poll_points(const std::vector<double>& x, double mesh) {
        std::vector<size_t> ordered;
        for (size_t i = 0; i < parameters_.size(); ++i) {
            if (parameters_[i].kind != ParameterKind::Enumerated && step_of(parameters_[i], mesh) > 0.0) {
                ordered.push_back(i);
            }
        }
        std::vector<std::vector<double>> points;
        if (ordered.size() < 2) return points;
        for (int k = 0; k < options_.random_directions; ++k) {
            const size_t first = ordered[random_.below(ordered.size())];
            size_t second = ordered[random_.below(ordered.size() - 1)];
            if (second == first) second = ordered.back();
            const double a = 2.0 * random_.uniform() - 1.0;
            const double b = 2.0 * random_.uniform() - 1.0;
            const double largest = std::max(std::fabs(a), std::fabs(b));
            if (largest == 0.0) continue;
            for (double sign : {1.0, -1.0}) {
                std::vector<double> point = x;
                point[first] += sign * a / largest * step_of(parameters_[first], mesh);
                point[second] += sign * b / largest * step_of(parameters_[second], mesh);
                point = snap_point(parameters_, point);
                if (point != x) points.push_back(std::move(point));
            }
        }
        return points;
    }

    // Compass search with pattern moves from `x`; true when the mesh fell below min_step, false when the budget
    // ran out.
    bool local_search(std::vector<double> x, Evaluation fx) {
        double mesh = options_.initial_step;
        std::vector<size_t> order(parameters_.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        while (true) {
            const std::vector<double> base = x;
            bool moved = false;
            random_.shuffle(order);
            for (size_t i : order) {
                for (const std::vector<double>& point : poll_points(x, i, mesh)) {
                    const std::optional<Evaluation> value = evaluate(point);
                    if (!value) return false;
                    if (better(*value, fx, options_.min_improvement)) {
                        if (parameters_[i].kind != ParameterKind::Enumerated) {
                            last_direction_[i] = point[i] > x[i] ? 1 : -1;
                        }
                        x = point;
                        fx = *value;
                        moved = true;
                        break;
                    }
                    if (parameters_[i].kind != ParameterKind::Enumerated) last_direction_[i] = 0;
                }
            }
            if (moved) {
                // Hooke-Jeeves: the sweep's whole move once more (enumerated levels have no direction: kept).
                std::vector<double> pattern = x;
                for (size_t i = 0; i < pattern.size(); ++i) {
                    if (parameters_[i].kind != ParameterKind::Enumerated) pattern[i] += x[i] - base[i];
                }
                pattern = snap_point(parameters_, pattern);
                if (pattern != x) {
                    const std::optional<Evaluation> value = evaluate(pattern);
                    if (!value) return false;
                    if (better(*value, fx, options_.min_improvement)) {
                        x = pattern;
                        fx = *value;
                    }
                }
                continue;
            }
            // Before the mesh shrinks, a few random directions: the compass directions alone stall on a constraint
            // that runs diagonally to them (a budget that two settings spend together).
            bool moved_randomly = false;
            for (const std::vector<double>& point : random_poll_points(x, mesh)) {
                const std::optional<Evaluation> value = evaluate(point);
                if (!value) return false;
                if (better(*value, fx, options_.min_improvement)) {
                    x = point;
                    fx = *value;
                    moved_randomly = true;
                    break;
                }
            }
            if (moved_randomly) continue;
            if (mesh * 0.5 < options_.min_step) return true;
            mesh *= 0.5;
        }
    }

    const std::vector<SearchParameter>& parameters_;
    const Objective& objective_;
    const SearchOptions& options_;
    SplitMix64 random_;
    std::vector<int> last_direction_;  // per coordinate: +1, -1, or 0 (none yet)
    std::map<std::vector<double>, Evaluation> cache_;
    SearchResult result_;
    int restart_ = 0;
};

}  // namespace

SearchParameter continuous_parameter(double scale) { return SearchParameter{ParameterKind::Continuous, 0, scale}; }
SearchParameter integer_parameter(int levels, double scale) {
    return SearchParameter{ParameterKind::Integer, levels, scale};
}
SearchParameter enumerated_parameter(int levels) { return SearchParameter{ParameterKind::Enumerated, levels, 1.0}; }

bool Evaluation::feasible() const { return violation <= 0.0 && std::isfinite(value); }

bool better(const Evaluation& a, const Evaluation& b, double margin) {
    const bool a_feasible = a.feasible();
    const bool b_feasible = b.feasible();
    if (a_feasible != b_feasible) return a_feasible;
    if (a_feasible) return a.value < b.value - margin;
    return a.violation < b.violation;
}

int level_of(const SearchParameter& parameter, double coordinate) {
    if (parameter.levels <= 1) return 0;
    const double clamped = std::isnan(coordinate) ? 0.0 : std::clamp(coordinate, 0.0, 1.0);
    return int(std::lround(clamped * double(parameter.levels - 1)));
}

double coordinate_of_level(const SearchParameter& parameter, int level) {
    if (parameter.levels <= 1) return 0.0;
    return double(std::clamp(level, 0, parameter.levels - 1)) / double(parameter.levels - 1);
}

std::vector<double> snap_point(const std::vector<SearchParameter>& parameters, const std::vector<double>& point) {
    if (point.size() != parameters.size()) {
        throw std::invalid_argument("a point of " + std::to_string(point.size()) + " coordinates for " +
                                    std::to_string(parameters.size()) + " parameters");
    }
    std::vector<double> snapped(point.size());
    for (size_t i = 0; i < point.size(); ++i) {
        if (is_discrete(parameters[i])) {
            snapped[i] = coordinate_of_level(parameters[i], level_of(parameters[i], point[i]));
        } else {
            const double clamped = std::isnan(point[i]) ? 0.0 : std::clamp(point[i], 0.0, 1.0);
            snapped[i] = std::round(clamped * kGrid) / kGrid;
        }
    }
    return snapped;
}

SearchResult pattern_search(const std::vector<SearchParameter>& parameters, const std::vector<double>& start,
                            const Objective& objective, const SearchOptions& options) {
    if (parameters.empty()) throw std::invalid_argument("pattern_search: no parameters");
    for (const SearchParameter& parameter : parameters) {
        if (is_discrete(parameter) && parameter.levels < 1) {
            throw std::invalid_argument("pattern_search: a discrete parameter with " +
                                        std::to_string(parameter.levels) + " levels");
        }
        if (!(parameter.scale > 0.0 && parameter.scale <= 1.0)) {
            throw std::invalid_argument("pattern_search: a parameter's scale outside (0, 1]");
        }
    }
    if (options.max_evaluations < 1) throw std::invalid_argument("pattern_search: max_evaluations < 1");
    if (options.random_directions < 0) throw std::invalid_argument("pattern_search: random_directions < 0");
    if (!(options.min_improvement >= 0.0)) throw std::invalid_argument("pattern_search: min_improvement < 0");
    if (!(options.initial_step > 0.0 && options.initial_step <= 1.0)) {
        throw std::invalid_argument("pattern_search: initial_step outside (0, 1]");
    }
    if (!(options.min_step > 0.0 && options.min_step <= options.initial_step)) {
        throw std::invalid_argument("pattern_search: min_step outside (0, initial_step]");
    }
    if (!objective) throw std::invalid_argument("pattern_search: no objective");
    return Search(parameters, objective, options).run(start);
}

}  // namespace obscura::samples
