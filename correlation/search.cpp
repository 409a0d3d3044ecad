#include "correlation/search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <sstream>

#include "correlation/emulator.hpp"
#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

/// Thrown inside the objective when the budget is spent: NLopt passes it through as
/// nlopt::forced_stop.
struct BudgetSpent {};

struct Counter {
    Evaluator* evaluator = nullptr;
    int limit = 0;
    int used = 0;
};

double objective(const std::vector<double>& u, std::vector<double>& /*gradient*/, void* data) {
    auto* c = static_cast<Counter*>(data);
    if (c->used >= c->limit) throw nlopt::forced_stop();
    ++c->used;
    const Evaluation e = c->evaluator->evaluate(to_values(c->evaluator->free(), u));
    return e.misfit;
}

/// Runs one NLopt algorithm on the unit cube from `start` with at most `limit` evaluations.
void run_nlopt(nlopt::algorithm algorithm, Counter& counter, std::vector<double> start,
               double initial_step) {
    const auto d = static_cast<unsigned>(start.size());
    nlopt::opt opt(algorithm, d);
    opt.set_lower_bounds(std::vector<double>(d, 0.0));
    opt.set_upper_bounds(std::vector<double>(d, 1.0));
    opt.set_min_objective(objective, &counter);
    opt.set_maxeval(std::max(1, counter.limit - counter.used));
    opt.set_xtol_abs(1e-3);
    if (initial_step > 0.0) opt.set_initial_step(initial_step);
    double value = 0.0;
    try {
        opt.optimize(start, value);
    } catch (const nlopt::forced_stop&) {
        // the budget is spent: what was evaluated is in the evaluator's history
    } catch (const nlopt::roundoff_limited&) {
        // the objective is noisy at this scale: the history holds the best found
    }
}

std::vector<double> best_by_misfit(const Evaluator& evaluator) {
    const auto& h = evaluator.history();
    const auto it = std::min_element(
        h.begin(), h.end(), [](const auto& a, const auto& b) { return a.misfit < b.misfit; });
    return it->values;
}

double distance2(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
    return s;
}

SearchOutcome direct(Evaluator& evaluator, const SearchOptions& options) {
    const auto& free = evaluator.free();
    const int d = static_cast<int>(free.size());
    std::vector<double> start(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) start[i] = free[i].start;
    Counter counter{&evaluator, options.budget, 0};
    ++counter.used;
    evaluator.evaluate(start);
    // Global: DIRECT-L (Gablonsky and Kelley 2001) divides the cube into rectangles and
    // samples the most promising ones, so a misfit with several valleys is not missed.
    counter.limit = std::max(counter.used + 1,
                             static_cast<int>(std::lround(options.global_share * options.budget)));
    run_nlopt(nlopt::GN_DIRECT_L, counter, std::vector<double>(free.size(), 0.5), 0.0);
    // Local: BOBYQA (Powell 2009) refines from the best point with a quadratic model; one
    // parameter has no quadratic model to build, so COBYLA takes it.
    counter.limit = options.budget;
    SearchOutcome outcome;
    if (counter.used < counter.limit) {
        const auto from = to_unit(free, best_by_misfit(evaluator));
        run_nlopt(d >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, counter, from, 0.05);
    }
    outcome.best_values = best_by_misfit(evaluator);
    outcome.evaluations = counter.used;
    outcome.stopped = counter.used >= options.budget
                          ? "the budget of " + std::to_string(options.budget) + " evaluations"
                          : "the local search converged (steps below 0.001 of each interval)";
    return outcome;
}

SearchOutcome surrogate(Evaluator& evaluator, const SearchOptions& options) {
    const auto& free = evaluator.free();
    const int d = static_cast<int>(free.size());
    std::vector<double> start(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) start[i] = free[i].start;
    const int initial =
        std::min(options.budget, options.initial_points > 0 ? options.initial_points : 2 * d + 2);
    // The start: the config's values and a Latin hypercube, simulated in parallel.
    std::vector<std::vector<double>> batch{start};
    for (const auto& u : latin_hypercube(initial - 1, d, 1)) batch.push_back(to_values(free, u));
    evaluator.evaluate(batch);
    int used = static_cast<int>(batch.size());

    const auto candidates = halton(1024, d);
    SearchOutcome outcome;
    outcome.stopped = "the budget of " + std::to_string(options.budget) + " evaluations";
    int small_in_a_row = 0;
    while (used < options.budget) {
        const FeatureEmulator emulator(evaluator.measurement(), free, evaluator.history());
        std::vector<std::vector<double>> seen;
        double best = std::numeric_limits<double>::infinity();
        std::vector<double> best_u;
        for (const auto& e : evaluator.history()) {
            seen.push_back(to_unit(free, e.values));
            if (!e.error.empty()) continue;
            const double m = emulator.misfit(seen.back());
            if (m < best) {
                best = m;
                best_u = seen.back();
            }
        }
        // Candidates: the space-filling set and a cloud around the best point, so the
        // acquisition can both explore and refine.
        std::vector<std::vector<double>> pool = candidates;
        for (const auto& z : halton(256, d, 2000)) {
            std::vector<double> u(d);
            for (int j = 0; j < d; ++j) u[j] = std::clamp(best_u[j] + 0.2 * (z[j] - 0.5), 0.0, 1.0);
            pool.push_back(u);
        }
        double top = -1.0;
        std::vector<double> next;
        for (const auto& u : pool) {
            const bool near = std::any_of(seen.begin(), seen.end(),
                                          [&](const auto& s) { return distance2(s, u) < 1e-6; });
            if (near) continue;
            const double ei = emulator.expected_improvement(u, best);
            if (ei > top) {
                top = ei;
                next = u;
            }
        }
        if (next.empty()) {
            outcome.stopped = "no candidate left away from the evaluated points";
            break;
        }
        if (top < options.improvement_tolerance) {
            if (++small_in_a_row >= 2) {
                std::ostringstream why;
                why << "the expected improvement fell below " << options.improvement_tolerance
                    << " twice in a row";
                outcome.stopped = why.str();
                break;
            }
        } else {
            small_in_a_row = 0;
        }
        evaluator.evaluate(to_values(free, next));
        ++used;
    }
    // The answer: the evaluated point the emulator, which averages the seed scatter, finds best.
    const FeatureEmulator emulator(evaluator.measurement(), free, evaluator.history());
    double best = std::numeric_limits<double>::infinity();
    for (const auto& e : evaluator.history()) {
        if (!e.error.empty()) continue;
        const double m = emulator.misfit(to_unit(free, e.values));
        if (m < best) {
            best = m;
            outcome.best_values = e.values;
        }
    }
    if (outcome.best_values.empty()) outcome.best_values = best_by_misfit(evaluator);
    outcome.evaluations = used;
    return outcome;
}

}  // namespace

std::string search_mode_name(SearchMode mode) {
    return mode == SearchMode::direct ? "direct" : "surrogate";
}

SearchOutcome search(Evaluator& evaluator, const SearchOptions& options) {
    return options.mode == SearchMode::direct ? direct(evaluator, options)
                                              : surrogate(evaluator, options);
}

}  // namespace sb::correlation
