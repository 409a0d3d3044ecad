// A characterisation run's progress as exact text.
#include "bench/characterization_progress.hpp"

#include <stdexcept>

#include "bench/checkpoint_text.hpp"

namespace sb::bench {
namespace {

/// The first line; sealed as a sweep checkpoint is.
constexpr const char* kMagic = "shakerbench-characterization-progress 1";
constexpr std::string_view kMagicPrefix = "shakerbench-characterization-progress ";

using checkpoint::read_count;
using checkpoint::Reader;
using checkpoint::Writer;

void write_complex(Writer& w, std::complex<double> z) { w.num(z.real()).num(z.imag()); }

std::complex<double> read_complex(Reader& r, std::istringstream& words) {
    const double re = r.num(words);
    return {re, r.num(words)};
}

}  // namespace

std::string serialize_run_progress(const RunProgress& p) {
    Writer w;
    w.key(kMagic).end();
    w.key("steps_per_period").integer(p.steps_per_period).end();
    if (!p.damper.dem)
        throw std::invalid_argument("a characterisation run's progress needs its bed");
    checkpoint::write_dem_state(w, *p.damper.dem);
    checkpoint::write_ledger(w, p.boundary);
    w.key("periods").integer(static_cast<long long>(p.periods.size())).end();
    for (const auto& period : p.periods) {
        w.key("period");
        write_complex(w, period.q1);
        write_complex(w, period.q2);
        write_complex(w, period.q3);
        w.num(period.wall_work_j).num(period.stored_at_start_j).num(period.kinetic_j).end();
    }
    const EnergySamples& e = p.energy;
    w.key("samples").integer(static_cast<long long>(e.kinetic_j.size())).end();
    if (!e.dissipated_j.empty()) w.key("dissipated_start").num(e.dissipated_j.front()).end();
    for (std::size_t k = 0; k < e.kinetic_j.size(); ++k) {
        w.key("s").num(e.kinetic_j[k]).num(e.dissipated_j[k + 1]).end();
    }
    w.key("ledgers").integer(static_cast<long long>(e.at.size())).end();
    for (const auto& ledger : e.at) checkpoint::write_ledger(w, ledger);
    w.key("end").end();
    return seal_checkpoint(w.str());
}

RunProgress parse_run_progress(const std::string& text, const std::string& file_name) {
    checkpoint::check_sealed(text, file_name, kMagic, kMagicPrefix);
    Reader r(std::string(checkpoint_content(text)), file_name);
    RunProgress p;
    r.line(kMagic);
    {
        auto words = r.line("steps_per_period");
        const long long n = r.integer(words);
        r.end(words);
        if (n < 1 || n > checkpoint::kMaxCount) r.fail("implausible steps per period");
        p.steps_per_period = static_cast<int>(n);
    }
    p.damper.dem = checkpoint::read_dem_state(r);
    p.boundary = checkpoint::read_ledger(r);
    const long long periods = read_count(r, "periods");
    for (long long k = 0; k < periods; ++k) {
        auto words = r.line("period");
        PeriodMeasurement period;
        period.q1 = read_complex(r, words);
        period.q2 = read_complex(r, words);
        period.q3 = read_complex(r, words);
        period.wall_work_j = r.num(words);
        period.stored_at_start_j = r.num(words);
        period.kinetic_j = r.num(words);
        r.end(words);
        p.periods.push_back(period);
    }
    const long long samples = read_count(r, "samples");
    if (samples > 0) {
        auto words = r.line("dissipated_start");
        p.energy.dissipated_j.push_back(r.num(words));
        r.end(words);
    }
    for (long long k = 0; k < samples; ++k) {
        auto words = r.line("s");
        p.energy.kinetic_j.push_back(r.num(words));
        p.energy.dissipated_j.push_back(r.num(words));
        r.end(words);
    }
    const long long ledgers = read_count(r, "ledgers");
    for (long long k = 0; k < ledgers; ++k) p.energy.at.push_back(checkpoint::read_ledger(r));
    r.line("end");
    if (!r.at_end()) r.fail("text follows 'end'");
    return p;
}

}  // namespace sb::bench
