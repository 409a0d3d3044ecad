// Refining a sweep's grid near its peak.
#include "bench/grid_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "identification/damping_curve.hpp"

namespace sb::bench {

namespace id = identification;

GridVerdict assess_grid(const std::vector<id::PointRow>& rows, bool base_excitation,
                        std::size_t max_new) {
    GridVerdict verdict;
    // The sweep's own recording: reference and control channel.
    id::Recording rec;
    rec.info.excitation = base_excitation ? "base" : "force";
    rec.channels.push_back({"reference", base_excitation ? "acceleration" : "force",
                            base_excitation ? "m/s^2" : "N", "", id::ChannelRole::reference});
    rec.channels.push_back({"control", "acceleration", "m/s^2", "", id::ChannelRole::control});
    for (const auto& row : rows) {
        id::PointRow p = row;
        p.values.resize(2);
        p.filling = 0;
        rec.points.push_back(std::move(p));
    }
    if (rec.points.empty()) return verdict;
    const auto levels = id::identify_recording(rec);
    if (levels.empty()) return verdict;
    const id::LevelIdentification& level = levels.front();
    if (level.half_power.ok() && level.circle_fit.ok()) {
        verdict.resolved = true;
        return verdict;
    }
    for (const auto* e : {&level.half_power, &level.circle_fit}) {
        if (e->ok()) continue;
        if (!verdict.unresolved_reason.empty()) verdict.unresolved_reason += "; ";
        verdict.unresolved_reason +=
            (e == &level.half_power ? "half-power: " : "circle fit: ") + e->message;
    }
    const auto& f = level.frf.frequency_hz;  // ascending, closest points left out
    const auto& h = level.frf.value;
    if (f.size() < 2 || max_new == 0) return verdict;
    std::size_t k = 0;
    for (std::size_t i = 1; i < h.size(); ++i) {
        if (std::abs(h[i]) > std::abs(h[k])) k = i;
    }
    const std::size_t last = f.size() - 1;
    const auto status = level.half_power.status;
    std::vector<double> add;
    if (k == 0 || status == id::EstimateStatus::no_lower_crossing) {
        add.push_back(f[0] - (f[1] - f[0]));  // one spacing below the grid
    }
    if (k == last || status == id::EstimateStatus::no_upper_crossing) {
        add.push_back(f[last] + (f[last] - f[last - 1]));  // one spacing above
    }
    if (add.empty()) {
        // The peak falls between points too far apart: halve the spacing on both sides.
        add.push_back(0.5 * (f[k - 1] + f[k]));
        add.push_back(0.5 * (f[k] + f[k + 1]));
    }
    std::erase_if(add, [&](double x) {
        return !(x > 0.0) || std::any_of(rows.begin(), rows.end(), [&](const id::PointRow& r) {
            return r.frequency_hz == x;
        });
    });
    std::sort(add.begin(), add.end());
    if (add.size() > max_new) add.resize(max_new);
    verdict.add_hz = add;
    return verdict;
}

}  // namespace sb::bench
