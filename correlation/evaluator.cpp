#include "correlation/evaluator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iomanip>
#include <sstream>
#include <thread>

#include "bench/resolved_config.hpp"
#include "core/text_file.hpp"

namespace sb::correlation {
namespace {

constexpr const char* kCacheMagic = "shakerbench-evaluation 2";

std::string number_text(double v) {
    if (!std::isfinite(v)) return "nan";
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
}

double parse_double(const std::string& text) {
    if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument("trailing characters");
    return v;
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(line);
    while (std::getline(in, part, sep)) parts.push_back(part);
    return parts;
}

}  // namespace

bench::CampaignResult coupled_simulation(const bench::CampaignConfig& config,
                                         const bench::Selection& selection, int threads) {
    bench::CampaignContext context;
    context.threads = threads;
    context.selection = selection;
    return bench::run_campaign(config, context);
}

std::string stable_hash(const std::string& text) {
    std::uint64_t h = 14695981039346656037ULL;
    for (const unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
    return buffer;
}

bool parse_evaluation_text(const std::string& text, const std::string& key, std::size_t features,
                           Evaluation& e) {
    try {
        std::istringstream in(text);
        std::string line;
        if (!std::getline(in, line) || line != kCacheMagic) return false;
        if (!std::getline(in, line) || line != "key\t" + key) return false;
        SimulatedFeatures s;
        std::string error;
        double wall = 0.0;
        bool ended = false;
        while (std::getline(in, line)) {
            const auto parts = split(line, '\t');
            if (parts.empty()) continue;
            if (parts[0] == "error" && parts.size() == 2) {
                error = parts[1];
            } else if (parts[0] == "wall_time_s" && parts.size() == 2) {
                wall = parse_double(parts[1]);
            } else if (parts[0] == "points_flagged" && parts.size() == 2) {
                s.points_flagged = std::stoi(parts[1]);
            } else if (parts[0] == "fillings" && parts.size() == 2) {
                s.fillings = std::stoi(parts[1]);
            } else if (parts[0] == "feature" && parts.size() == 3) {
                s.value.push_back(parse_double(parts[1]));
                s.sigma.push_back(parse_double(parts[2]));
            } else if (parts[0] == "damping" && parts.size() == 9) {
                identification::DampingRow r;
                r.arrangement = parts[1];
                r.level_g = parse_double(parts[2]);
                r.method = parts[3];
                r.natural_frequency_hz = parse_double(parts[4]);
                r.damping_ratio = parse_double(parts[5]);
                r.fillings = std::stoi(parts[6]);
                r.natural_frequency_std_hz = parse_double(parts[7]);
                r.damping_ratio_std = parse_double(parts[8]);
                s.damping.push_back(r);
            } else if (parts[0] == "end") {
                ended = true;
            } else {
                return false;
            }
        }
        if (!ended) return false;
        if (error.empty() && s.value.size() != features) return false;
        e.simulated = s;
        e.error = error;
        e.wall_time_s = wall;
    } catch (const std::exception&) {
        return false;
    }
    e.key = key;
    return true;
}

std::string evaluation_text(const Evaluation& e) {
    std::ostringstream out;
    out << kCacheMagic << '\n' << "key\t" << e.key << '\n';
    std::string error = e.error;
    std::replace(error.begin(), error.end(), '\n', ' ');
    std::replace(error.begin(), error.end(), '\t', ' ');
    if (!error.empty()) out << "error\t" << error << '\n';
    out << "wall_time_s\t" << number_text(e.wall_time_s) << '\n';
    out << "points_flagged\t" << e.simulated.points_flagged << '\n';
    out << "fillings\t" << e.simulated.fillings << '\n';
    for (std::size_t i = 0; i < e.simulated.value.size(); ++i) {
        out << "feature\t" << number_text(e.simulated.value[i]) << '\t'
            << number_text(e.simulated.sigma[i]) << '\n';
    }
    for (const auto& r : e.simulated.damping) {
        out << "damping\t" << r.arrangement << '\t' << number_text(r.level_g) << '\t' << r.method
            << '\t' << number_text(r.natural_frequency_hz) << '\t' << number_text(r.damping_ratio)
            << '\t' << r.fillings << '\t' << number_text(r.natural_frequency_std_hz) << '\t'
            << number_text(r.damping_ratio_std) << '\n';
    }
    out << "end\n";
    return out.str();
}

Evaluator::Evaluator(bench::CampaignConfig config, std::vector<FreeParameter> free,
                     Measurement measurement, EvaluatorOptions options)
    : config_(std::move(config)),
      free_(std::move(free)),
      measurement_(std::move(measurement)),
      options_(std::move(options)) {
    if (!options_.simulate) options_.simulate = coupled_simulation;
    // The layout: which points are simulated and which features are compared. Two
    // measurements with the same layout share the cached simulations.
    std::string layout = measurement_.response_channel + "|" + measurement_.damping_method + "\n";
    if (!options_.fidelity.empty()) layout += "fidelity " + options_.fidelity + "\n";
    for (const auto& sweep : measurement_.selection.sweeps) {
        layout += sweep.arrangement + " " + number_text(sweep.level_g);
        for (double f : sweep.frequencies_hz) layout += " " + number_text(f);
        layout += "\n";
    }
    for (const auto& f : measurement_.features) layout += f.label() + "\n";
    layout_hash_ = stable_hash(layout);
}

void Evaluator::compare(Evaluation& e) const {
    e.residuals.assign(measurement_.features.size(), 0.0);
    e.misfit = 0.0;
    if (!e.error.empty() || e.simulated.value.size() != measurement_.features.size()) {
        e.misfit = kFailedMisfit;
        return;
    }
    for (std::size_t i = 0; i < measurement_.features.size(); ++i) {
        e.residuals[i] = residual(measurement_.features[i], e.simulated.value[i],
                                  e.simulated.sigma[i], e.simulated.fillings);
        e.misfit += 0.5 * e.residuals[i] * e.residuals[i];
    }
}

bool Evaluator::prepare(const std::vector<double>& values, Evaluation& e,
                        bench::CampaignConfig& changed) const {
    e.values = values;
    try {
        changed = with_values(config_, free_, values);
    } catch (const std::exception& ex) {
        e.error = ex.what();
        e.key = stable_hash(e.error) + "-" + layout_hash_;
        compare(e);
        return false;
    }
    e.key = bench::config_hash(changed) + "-" + layout_hash_;
    return true;
}

void Evaluator::simulate(const bench::CampaignConfig& changed, Evaluation& e, int threads) const {
    const auto start = std::chrono::steady_clock::now();
    try {
        const bench::CampaignResult result =
            options_.simulate(changed, measurement_.selection, threads);
        e.simulated = simulated_features(result, measurement_);
    } catch (const std::exception& ex) {
        e.error = ex.what();
    }
    e.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Evaluation Evaluator::run_one(const std::vector<double>& values, int threads) const {
    Evaluation e;
    bench::CampaignConfig changed;
    if (!prepare(values, e, changed)) return e;
    if (load(e.key, e)) return e;
    simulate(changed, e, threads);
    compare(e);
    store(e);
    return e;
}

std::string Evaluator::simulate_text(const std::string& values_text, int threads) const {
    std::vector<double> values;
    for (const auto& part : split(values_text, ' ')) {
        if (!part.empty()) values.push_back(parse_double(part));
    }
    if (values.size() != free_.size()) {
        throw std::invalid_argument("an evaluation's values: " + std::to_string(values.size()) +
                                    " numbers for " + std::to_string(free_.size()) +
                                    " free values");
    }
    Evaluation e;
    bench::CampaignConfig changed;
    if (prepare(values, e, changed)) simulate(changed, e, threads);
    return evaluation_text(e);
}

std::vector<Evaluation> Evaluator::evaluate_remotely(
    const std::vector<std::vector<double>>& batch) {
    std::vector<Evaluation> results(batch.size());
    std::vector<std::size_t> missing;
    std::vector<std::string> inputs;
    for (std::size_t i = 0; i < batch.size(); ++i) {
        bench::CampaignConfig changed;
        if (!prepare(batch[i], results[i], changed) || load(results[i].key, results[i])) continue;
        missing.push_back(i);
        std::string text;
        for (const double v : batch[i]) text += (text.empty() ? "" : " ") + number_text(v);
        inputs.push_back(text);
    }
    if (!inputs.empty()) {
        const auto outputs = options_.remote(inputs);
        for (std::size_t k = 0; k < missing.size(); ++k) {
            Evaluation& e = results[missing[k]];
            const std::string key = e.key;
            if (k >= outputs.size() ||
                !parse_evaluation_text(outputs[k], key, measurement_.features.size(), e)) {
                e.error = k < outputs.size() ? "the evaluation's result did not read: " + outputs[k]
                                             : "the evaluation gave no result";
                e.key = key;
            }
            e.from_cache = false;
            compare(e);
            store(e);
        }
    }
    return results;
}

std::vector<Evaluation> Evaluator::evaluate(const std::vector<std::vector<double>>& batch) {
    if (options_.remote) {
        auto results = evaluate_remotely(batch);
        record(results);
        return results;
    }
    std::vector<Evaluation> results(batch.size());
    const int hardware = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    const int threads = options_.threads > 0 ? options_.threads : hardware;
    const int workers = std::max(1, std::min(threads, static_cast<int>(batch.size())));
    const int per_simulation = std::max(1, threads / workers);
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
        for (std::size_t i = next++; i < batch.size(); i = next++) {
            results[i] = run_one(batch[i], per_simulation);
        }
    };
    if (workers == 1) {
        work();
    } else {
        std::vector<std::thread> pool;
        for (int w = 0; w < workers; ++w) pool.emplace_back(work);
        for (auto& t : pool) t.join();
    }
    record(results);
    return results;
}

void Evaluator::record(const std::vector<Evaluation>& results) {
    for (const auto& e : results) {
        simulations_ += e.from_cache ? 0 : 1;
        history_.push_back(e);
        if (options_.progress) {
            std::ostringstream line;
            if (!options_.fidelity.empty()) line << options_.fidelity << ' ';
            line << "evaluation " << history_.size();
            if (options_.expected_evaluations > 0) line << " of ~" << options_.expected_evaluations;
            line << ":";
            line << std::setprecision(6);
            for (std::size_t i = 0; i < free_.size(); ++i) {
                line << ' ' << free_[i].path << '=' << e.values[i];
            }
            if (e.error.empty()) {
                line << "  misfit " << std::setprecision(4) << e.misfit;
            } else {
                line << "  failed: " << e.error;
            }
            double best = kFailedMisfit;
            double simulated_time = 0.0;
            for (const auto& h : history_) {
                best = std::min(best, h.misfit);
                if (!h.from_cache) simulated_time += h.wall_time_s;
            }
            line << ", best " << best;
            if (e.from_cache) {
                line << "  (cached)";
            } else {
                line << "  (" << std::fixed << std::setprecision(1) << e.wall_time_s << " s)";
            }
            const auto done = static_cast<int>(history_.size());
            if (options_.expected_evaluations > done && simulations_ > 0) {
                // Batches run side by side, so the ETA from the mean simulation time is an
                // upper bound.
                const double eta = (options_.expected_evaluations - done) * simulated_time /
                                   static_cast<double>(simulations_);
                line << ", ETA " << std::setprecision(0) << eta << " s for "
                     << options_.expected_evaluations - done << " more";
            }
            options_.progress(line.str());
        }
    }
}

Evaluation Evaluator::evaluate(const std::vector<double>& values) {
    return evaluate(std::vector<std::vector<double>>{values}).front();
}

bool Evaluator::load(const std::string& key, Evaluation& e) const {
    for (const auto& h : history_) {
        if (h.key == key) {
            const auto values = e.values;
            e = h;
            e.values = values;
            e.from_cache = true;
            return true;
        }
    }
    if (options_.cache_dir.empty()) return false;
    const auto file = options_.cache_dir / (key + ".txt");
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return false;
    // A file that does not parse whole (cut short, edited, another version) is simulated again
    // rather than half believed.
    std::string text;
    try {
        text = read_text_file(file);
    } catch (const std::exception&) {
        return false;
    }
    if (!parse_evaluation_text(text, key, measurement_.features.size(), e)) return false;
    e.key = key;
    e.from_cache = true;
    compare(e);
    return true;
}

void Evaluator::store(const Evaluation& e) const {
    if (options_.cache_dir.empty()) return;
    const std::string text = evaluation_text(e);
    std::filesystem::create_directories(options_.cache_dir);
    write_file_atomically(options_.cache_dir / (e.key + ".txt"), text);
}

}  // namespace sb::correlation
