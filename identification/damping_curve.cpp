// Damping versus level: per arrangement and level, FRF and the three estimators.
#include "identification/damping_curve.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "core/units.hpp"
#include "identification/energy.hpp"

namespace sb::identification {

namespace {

void subtract(ModalEstimate& e, double background) {
    if (e.ok()) e.damping_ratio = subtract_background(e.damping_ratio, background);
}

}  // namespace

LevelIdentification identify_frf(const std::string& arrangement, double level_g, const Frf& frf,
                                 const IdentifyOptions& options, bool force_reference) {
    LevelIdentification l;
    l.arrangement = arrangement;
    l.level_g = level_g;
    l.frf = frf;
    if (options.effective_mass_kg > 0.0 && force_reference && !frf.value.empty()) {
        // W/T (paper 003) at the point of largest response; W = π Im(F conj X) and
        // T = ½ m ω²|X|² with X from the response amplitude per unit force (F = 1 N).
        const Frf receptance = convert(l.frf, FrfForm::receptance);
        std::size_t k = 0;
        for (std::size_t i = 1; i < receptance.value.size(); ++i) {
            if (std::abs(receptance.value[i]) > std::abs(receptance.value[k])) k = i;
        }
        const double w = hz_to_rad_s(receptance.frequency_hz[k]);
        const std::complex<double> x = receptance.value[k];
        const double psi =
            specific_damping_capacity(dissipated_energy_per_cycle(1.0, x),
                                      kinetic_energy_amplitude(options.effective_mass_kg, w, x));
        l.specific_damping_capacity = psi - 4.0 * kPi * options.background_damping_ratio;
        l.capacity_frequency_hz = receptance.frequency_hz[k];
    }
    CircleFitOptions circle = options.circle;
    circle.residual = options.residual;
    RationalFractionOptions rfp = options.rational_fraction;
    rfp.residual = options.residual;
    l.half_power = half_power(l.frf, options.half_power_form, options.residual);
    l.circle_fit = circle_fit(l.frf, circle);
    l.rational_fraction = rational_fraction_fit(l.frf, rfp);
    for (auto* e : {&l.half_power, &l.circle_fit, &l.rational_fraction}) {
        subtract(*e, options.background_damping_ratio);
    }
    return l;
}

std::vector<LevelIdentification> identify_recording(const Recording& rec,
                                                    const IdentifyOptions& options) {
    const std::size_t ref = rec.reference_index();
    std::size_t resp = rec.channels.size();
    std::string names;
    for (const auto& ch : rec.channels) names += (names.empty() ? "" : ", ") + ch.name;
    if (!options.response_channel.empty()) {
        resp = rec.channel_index(options.response_channel);
        if (resp == rec.channels.size()) {
            throw std::invalid_argument("no channel '" + options.response_channel +
                                        "' in recording.toml (channels: " + names + ")");
        }
        if (resp == ref) {
            throw std::invalid_argument("channel '" + options.response_channel +
                                        "' is the reference: choose a response channel (" + names +
                                        ")");
        }
    } else {
        for (std::size_t i = 0; i < rec.channels.size() && resp == rec.channels.size(); ++i) {
            if (rec.channels[i].role == ChannelRole::control) resp = i;
        }
        for (std::size_t i = 0; i < rec.channels.size() && resp == rec.channels.size(); ++i) {
            if (rec.channels[i].role == ChannelRole::response) resp = i;
        }
    }
    if (resp == rec.channels.size() || ref == rec.channels.size()) {
        throw std::invalid_argument("recording.toml has no control or response channel (" + names +
                                    ")");
    }
    const std::string& quantity = rec.channels[resp].quantity;
    const bool base = rec.info.excitation == "base";
    FrfForm form = FrfForm::accelerance;
    if (!base && quantity == "velocity") form = FrfForm::mobility;
    if (!base && quantity == "displacement") form = FrfForm::receptance;

    // Repeats (same frequency) are combined by H1 = Σ Y conj(X) / Σ |X|² over them (Bendat &
    // Piersol): Y/X for a single point, and noise on the response averages out.
    struct Spectra {
        std::complex<double> cross;  ///< Σ Y conj(X)
        double reference = 0.0;      ///< Σ |X|²
    };
    // One FRF per arrangement, level and filling of the bed.
    using Key = std::tuple<std::string, double, int>;
    std::vector<Key> order;
    std::map<Key, std::map<double, Spectra>> groups;
    std::map<Key, std::vector<double>> closest;
    std::map<Key, std::set<std::string>> statuses;
    const bool skip = options.closest == ClosestPolicy::skip;
    for (const auto& p : rec.points) {
        const Key key{p.arrangement, p.level_g, p.filling};
        if (groups.find(key) == groups.end()) {
            order.push_back(key);
            groups[key];  // the level keeps its place even if every point is left out
        }
        if (left_out_of_fits_by_default(p.status)) {
            closest[key].push_back(p.frequency_hz);
            statuses[key].insert(p.status);
            if (skip) continue;
        }
        const std::complex<double> x = p.values[ref].amplitude;
        std::complex<double> y = p.values[resp].amplitude;
        if (base) y -= x;  // relative transmissibility (response − table)/table
        auto& cell = groups[key][p.frequency_hz];
        cell.cross += y * std::conj(x);
        cell.reference += std::norm(x);
    }
    const bool force_reference = !base && rec.channels[ref].quantity == "force";
    std::vector<LevelIdentification> out;
    for (const auto& key : order) {
        Frf frf;
        frf.form = form;
        for (const auto& [f, sum] : groups[key]) {
            frf.frequency_hz.push_back(f);
            frf.value.push_back(sum.cross / sum.reference);
        }
        out.push_back(
            identify_frf(std::get<0>(key), std::get<1>(key), frf, options, force_reference));
        out.back().filling = std::get<2>(key);
        out.back().channel = rec.channels[resp].name;
        auto& flagged = skip ? out.back().skipped_hz : out.back().closest_used_hz;
        flagged = closest[key];
        std::sort(flagged.begin(), flagged.end());
        for (const char* status : kPointStatuses) {
            if (statuses[key].count(status) != 0) out.back().flagged_statuses.push_back(status);
        }
    }
    return out;
}

namespace {

/// The row of one estimate of one filling.
DampingRow row_of(const LevelIdentification& l, Method m, const ModalEstimate& e) {
    DampingRow r;
    r.arrangement = l.arrangement;
    r.level_g = l.level_g;
    r.natural_frequency_hz = e.natural_frequency_hz;
    r.damping_ratio = e.damping_ratio;
    r.method = std::string(to_string(m));
    r.points_used = e.points_used;
    r.frequencies_used_hz = e.frequencies_used_hz;
    r.points_skipped = static_cast<int>(l.skipped_hz.size());
    return r;
}

template <class Each>
void for_each_estimate(const LevelIdentification& l, bool include_rational_fraction, Each each) {
    const std::pair<Method, const ModalEstimate*> all[] = {
        {Method::half_power, &l.half_power},
        {Method::circle_fit, &l.circle_fit},
        {Method::rational_fraction, &l.rational_fraction}};
    for (const auto& [m, e] : all) {
        if (!e->ok() || (m == Method::rational_fraction && !include_rational_fraction)) continue;
        each(m, *e);
    }
}

/// Mean and sample standard deviation (0 for one value).
std::pair<double, double> mean_and_spread(const std::vector<double>& v) {
    double mean = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    if (v.size() < 2) return {mean, 0.0};
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    return {mean, std::sqrt(ss / static_cast<double>(v.size() - 1))};
}

}  // namespace

std::vector<DampingRow> filling_damping_rows(const std::vector<LevelIdentification>& levels,
                                             bool include_rational_fraction) {
    std::vector<DampingRow> rows;
    for (const auto& l : levels) {
        for_each_estimate(l, include_rational_fraction, [&](Method m, const ModalEstimate& e) {
            rows.push_back(row_of(l, m, e));
            rows.back().filling = l.filling;
        });
    }
    return rows;
}

std::vector<DampingRow> damping_rows(const std::vector<LevelIdentification>& levels,
                                     bool include_rational_fraction) {
    // Rows of every filling, gathered per arrangement, level and method in order of first
    // appearance, then each group reduced to its mean and scatter.
    using Key = std::tuple<std::string, double, std::string>;
    std::vector<Key> order;
    std::map<Key, std::vector<DampingRow>> groups;
    for (const auto& row : filling_damping_rows(levels, include_rational_fraction)) {
        const Key key{row.arrangement, row.level_g, row.method};
        if (groups.find(key) == groups.end()) order.push_back(key);
        groups[key].push_back(row);
    }
    std::vector<DampingRow> rows;
    for (const auto& key : order) {
        const auto& group = groups[key];
        DampingRow r = group.front();
        r.filling = -1;
        r.fillings = static_cast<int>(group.size());
        if (group.size() > 1) {
            std::vector<double> f;
            std::vector<double> zeta;
            std::vector<double> used;
            r.points_used = 0;
            r.points_skipped = 0;
            for (const auto& g : group) {
                f.push_back(g.natural_frequency_hz);
                zeta.push_back(g.damping_ratio);
                r.points_used += g.points_used;
                r.points_skipped += g.points_skipped;
                used.insert(used.end(), g.frequencies_used_hz.begin(), g.frequencies_used_hz.end());
            }
            std::tie(r.natural_frequency_hz, r.natural_frequency_std_hz) = mean_and_spread(f);
            std::tie(r.damping_ratio, r.damping_ratio_std) = mean_and_spread(zeta);
            std::sort(used.begin(), used.end());
            r.frequencies_used_hz = used;
        }
        rows.push_back(std::move(r));
    }
    return rows;
}

}  // namespace sb::identification
