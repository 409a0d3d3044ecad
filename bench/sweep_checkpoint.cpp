// Sweep checkpoints: exact text form of a sweep's progress and state.
#include "bench/sweep_checkpoint.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "bench/checkpoint_text.hpp"
#include "config/write.hpp"

namespace sb::bench {
namespace {

using checkpoint::check_sealed;
using checkpoint::kChecksumKey;
using checkpoint::kMaxCount;
using checkpoint::kMaxVectorSize;
using checkpoint::read_count;
using checkpoint::read_dem_state;
using checkpoint::read_vector;
using checkpoint::Reader;
using checkpoint::write_dem_state;
using checkpoint::write_vector;
using checkpoint::Writer;

/// The first line. Format 4 added the checksum line, 5 the numerics line.
constexpr const char* kMagic = "shakerbench-sweep-checkpoint 5";
constexpr std::string_view kMagicPrefix = "shakerbench-sweep-checkpoint ";
/// Points no sweep reaches: a count past it is damage.
constexpr long long kMaxPoints = 1000000;
/// The first line of a pour's progress (settled_bed.hpp); sealed as a sweep checkpoint is.
constexpr const char* kPourMagic = "shakerbench-pour-progress 1";
constexpr std::string_view kPourMagicPrefix = "shakerbench-pour-progress ";
/// The first line of a finished sweep sent from one process to another (no checksum: the
/// transport carries it whole).
constexpr const char* kResultMagic = "shakerbench-sweep-result 1";

void write_rows(Writer& w, const std::vector<identification::PointRow>& rows) {
    w.key("rows").integer(static_cast<long long>(rows.size())).end();
    for (const auto& row : rows) {
        w.key("row")
            .num(row.level_g)
            .num(row.frequency_hz)
            .integer(static_cast<long long>(row.values.size()));
        for (const auto& v : row.values) {
            w.num(v.rms)
                .num(v.amplitude.real())
                .num(v.amplitude.imag())
                .num(v.h2_ratio)
                .num(v.h3_ratio);
        }
        w.text(row.arrangement).text(row.status).text(row.series.empty() ? "-" : row.series);
        w.end();
    }
}

/// The rows of finished points; `expected` (when not negative) is the count the header
/// announced, checked before any row is read.
std::vector<identification::PointRow> read_rows(Reader& r, long long expected = -1) {
    std::vector<identification::PointRow> out;
    const long long rows = read_count(r, "rows");
    if (expected >= 0 && rows != expected) {
        r.fail(std::to_string(rows) + " rows for " + std::to_string(expected) + " finished points");
    }
    for (long long i = 0; i < rows; ++i) {
        auto words = r.line("row");
        identification::PointRow row;
        row.level_g = r.num(words);
        row.frequency_hz = r.num(words);
        const long long values = r.integer(words);
        if (values < 0 || values > kMaxVectorSize) {
            r.fail("implausible number of channels " + std::to_string(values));
        }
        for (long long k = 0; k < values; ++k) {
            identification::ChannelValue v;
            v.rms = r.num(words);
            const double re = r.num(words);
            const double im = r.num(words);
            v.amplitude = {re, im};
            v.h2_ratio = r.num(words);
            v.h3_ratio = r.num(words);
            row.values.push_back(v);
        }
        // The numbers end where the tab-separated texts begin.
        std::string rest;
        std::getline(words, rest);
        std::istringstream fields(rest);
        std::string numbers_left;
        std::getline(fields, numbers_left, '\t');
        if (numbers_left.find_first_not_of(' ') != std::string::npos) {
            r.fail("more numbers than the " + std::to_string(values) + " channels announced");
        }
        std::string extra;
        if (!std::getline(fields, row.arrangement, '\t') ||
            !std::getline(fields, row.status, '\t') || !std::getline(fields, row.series, '\t') ||
            std::getline(fields, extra, '\t')) {
            r.fail("a row holds its arrangement, status and series, and nothing more");
        }
        if (row.series == "-") {
            row.series.clear();
        }
        out.push_back(std::move(row));
    }
    return out;
}

using Series = std::vector<double>;

void write_series(Writer& w, const char* key, const Series& v) {
    checkpoint::write_vector(
        w, key, Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
}

Series read_series(Reader& r, const char* key) {
    const Eigen::VectorXd v = read_vector(r, key);
    return {v.data(), v.data() + v.size()};
}

/// A random test's progress: its numbers, the overlapping half segment, the Welch sums.
void write_random(Writer& w, const RandomProgress& p) {
    w.key("random")
        .integer(p.level_segments)
        .integer(p.level_done ? 1 : 0)
        .num(p.drive_rms)
        .num(p.level_rms)
        .integer(p.halves)
        .end();
    w.key("tail").integer(static_cast<long long>(p.tail.size())).end();
    for (const auto& channel : p.tail) write_series(w, "t", channel);
    const auto& sums = p.sums;
    w.key("welch")
        .integer(sums.segments)
        .integer(static_cast<long long>(sums.response.size()))
        .end();
    write_series(w, "gxx", sums.reference);
    for (std::size_t c = 0; c < sums.response.size(); ++c) {
        write_series(w, "gyy", sums.response[c]);
        Series re, im;
        for (const auto& v : sums.cross[c]) {
            re.push_back(v.real());
            im.push_back(v.imag());
        }
        write_series(w, "gxy_re", re);
        write_series(w, "gxy_im", im);
    }
}

RandomProgress read_random(Reader& r) {
    RandomProgress p;
    auto words = r.line("random");
    const long long level_segments = r.integer(words);
    const long long level_done = r.integer(words);
    p.drive_rms = r.num(words);
    p.level_rms = r.num(words);
    const long long halves = r.integer(words);
    r.end(words);
    if (level_segments < 0 || level_segments > kMaxCount || halves < 0 || halves > kMaxCount ||
        (level_done != 0 && level_done != 1) || !(p.drive_rms >= 0.0)) {
        r.fail("implausible random test progress");
    }
    p.level_segments = static_cast<int>(level_segments);
    p.level_done = level_done == 1;
    p.halves = static_cast<int>(halves);
    const long long tails = read_count(r, "tail");
    if (tails > 64) r.fail("implausible channel count " + std::to_string(tails));
    for (long long c = 0; c < tails; ++c) p.tail.push_back(read_series(r, "t"));
    auto welch = r.line("welch");
    const long long segments = r.integer(welch);
    const long long channels = r.integer(welch);
    r.end(welch);
    if (segments < 0 || segments > kMaxCount || channels < 0 || channels > 64) {
        r.fail("implausible Welch sums");
    }
    p.sums.segments = static_cast<int>(segments);
    p.sums.reference = read_series(r, "gxx");
    for (long long c = 0; c < channels; ++c) {
        p.sums.response.push_back(read_series(r, "gyy"));
        const Series re = read_series(r, "gxy_re");
        const Series im = read_series(r, "gxy_im");
        const std::size_t bins = p.sums.reference.size();
        if (p.sums.response.back().size() != bins || re.size() != bins || im.size() != bins) {
            r.fail("Welch sums of differing lengths");
        }
        std::vector<std::complex<double>> cross(bins);
        for (std::size_t k = 0; k < bins; ++k) cross[k] = {re[k], im[k]};
        p.sums.cross.push_back(std::move(cross));
    }
    return p;
}

/// "KEY n", then n lines "LINE_KEY<tab>text".
void write_lines(Writer& w, const char* key, const char* line_key,
                 const std::vector<std::string>& lines) {
    w.key(key).integer(static_cast<long long>(lines.size())).end();
    for (const auto& l : lines) {
        w.key(line_key).text(l).end();
    }
}

/// `expected` (when not negative): the count the header announced.
std::vector<std::string> read_lines(Reader& r, const char* key, const char* line_key,
                                    long long expected = -1) {
    std::vector<std::string> out;
    const long long count = read_count(r, key);
    if (expected >= 0 && count != expected) {
        r.fail(std::to_string(count) + " control log lines for " + std::to_string(expected) +
               " finished points");
    }
    for (long long i = 0; i < count; ++i) {
        r.line(line_key);
        out.push_back(r.text());
    }
    return out;
}

}  // namespace

std::string serialize_checkpoint(const SweepCheckpoint& c) {
    Writer w;
    w.key(kMagic).end();
    w.key("config_hash").text(c.config_hash).end();
    w.key("numerics").text(c.numerics).end();
    w.key("points_done").integer(c.points_done).end();
    w.key("next_amplitude").num(c.next_amplitude).end();
    write_vector(w, "q", c.state.q);
    write_vector(w, "q_dot", c.state.q_dot);
    w.key("attachments").integer(static_cast<long long>(c.state.attachments.size())).end();
    for (std::size_t d = 0; d < c.state.attachments.size(); ++d) {
        const auto& a = c.state.attachments[d];
        w.key("attachment")
            .text(a.dem              ? "dem"
                  : a.describing     ? "describing"
                  : a.sliders        ? "sliders"
                  : a.coil_current_a ? "coil"
                                     : "none")
            .end();
        w.key("load");
        for (int k = 0; k < 6; ++k) w.num(c.state.loads[d][k]);
        w.end();
        if (a.dem) write_dem_state(w, *a.dem);
        if (a.describing) {
            w.key("describing")
                .num(a.describing->acceleration_m_s2)
                .num(a.describing->mean_displacement_m)
                .end();
        }
        if (a.sliders)
            write_vector(w, "sliders",
                         Eigen::Map<const Eigen::VectorXd>(a.sliders->data(), a.sliders->size()));
        if (a.coil_current_a) w.key("coil").num(*a.coil_current_a).end();
    }
    write_rows(w, c.rows);
    write_lines(w, "log", "l", c.control_log);
    write_lines(w, "energy", "e", c.energy_log);
    if (c.transient_periods > 0) {
        // Only a run from rest writes it: a stepped sine's checkpoint reads as before.
        w.key("transient").integer(c.transient_periods).end();
        write_lines(w, "series", "s", c.transient_series);
        write_lines(w, "envelope", "v", c.transient_envelope);
    }
    if (c.random) write_random(w, *c.random);
    w.key("end").end();
    return seal_checkpoint(w.str());
}

CheckpointError::CheckpointError(std::string file, int line, std::string message)
    : std::runtime_error(file + ":" + (line > 0 ? std::to_string(line) + ":" : std::string()) +
                         " " + message),
      file_(std::move(file)),
      line_(line),
      message_(std::move(message)) {}

std::string seal_checkpoint(std::string_view content) {
    std::string text(content);
    text += kChecksumKey;
    text += config::fnv1a_hex(content);
    text += '\n';
    return text;
}

std::string_view checkpoint_content(std::string_view text) {
    if (text.empty() || text.back() != '\n') return text;
    const auto previous = text.find_last_of('\n', text.size() - 2);
    const std::size_t start = previous == std::string_view::npos ? 0 : previous + 1;
    if (text.substr(start).rfind(kChecksumKey, 0) != 0) return text;
    return text.substr(0, start);
}

SweepCheckpoint parse_checkpoint(const std::string& text, const std::string& file_name) {
    check_sealed(text, file_name, kMagic, kMagicPrefix);
    Reader r(std::string(checkpoint_content(text)), file_name);
    SweepCheckpoint c;
    r.line(kMagic);
    r.line("config_hash");
    c.config_hash = r.text();
    r.line("numerics");
    c.numerics = r.text();
    {
        auto words = r.line("points_done");
        const long long done = r.integer(words);
        if (done < 0 || done > kMaxPoints)
            r.fail("implausible points_done " + std::to_string(done));
        c.points_done = static_cast<int>(done);
        r.end(words);
    }
    {
        auto words = r.line("next_amplitude");
        c.next_amplitude = r.num(words);
        r.end(words);
    }
    c.state.q = read_vector(r, "q");
    c.state.q_dot = read_vector(r, "q_dot");
    if (c.state.q.size() != c.state.q_dot.size()) {
        r.fail("q_dot has " + std::to_string(c.state.q_dot.size()) + " values, q " +
               std::to_string(c.state.q.size()));
    }
    const long long attachments = read_count(r, "attachments");
    for (long long d = 0; d < attachments; ++d) {
        r.line("attachment");
        const std::string kind = r.text();
        if (kind != "dem" && kind != "describing" && kind != "sliders" && kind != "coil" &&
            kind != "none") {
            r.fail("unknown attachment '" + kind + "'");
        }
        auto load = r.line("load");
        Eigen::Matrix<double, 6, 1> l;
        for (int k = 0; k < 6; ++k) l[k] = r.num(load);
        r.end(load);
        c.state.loads.push_back(l);
        AttachmentState a;
        if (kind == "dem") a.dem = read_dem_state(r);
        if (kind == "describing") {
            auto words = r.line("describing");
            DescribingState described;
            described.acceleration_m_s2 = r.num(words);
            described.mean_displacement_m = r.num(words);
            a.describing = described;
        }
        if (kind == "sliders") {
            const Eigen::VectorXd sliders = read_vector(r, "sliders");
            a.sliders = std::vector<double>(sliders.data(), sliders.data() + sliders.size());
        }
        if (kind == "coil") {
            auto words = r.line("coil");
            a.coil_current_a = r.num(words);
            r.end(words);
        }
        c.state.attachments.push_back(std::move(a));
    }
    c.rows = read_rows(r, c.points_done);
    c.control_log = read_lines(r, "log", "l", c.points_done);
    c.energy_log = read_lines(r, "energy", "e");
    if (r.next_is("transient")) {
        auto words = r.line("transient");
        const long long periods = r.integer(words);
        if (periods < 0 || periods > kMaxCount) {
            r.fail("implausible transient periods " + std::to_string(periods));
        }
        r.end(words);
        c.transient_periods = static_cast<int>(periods);
        c.transient_series = read_lines(r, "series", "s");
        c.transient_envelope = read_lines(r, "envelope", "v");
        if (static_cast<long long>(c.transient_envelope.size()) != periods) {
            r.fail(std::to_string(c.transient_envelope.size()) + " envelope rows for " +
                   std::to_string(periods) + " periods run");
        }
    }
    if (r.next_is("random")) c.random = read_random(r);
    {
        auto words = r.line("end");
        r.end(words);
    }
    if (!r.at_end()) r.fail("text follows 'end'");
    return c;
}

std::string serialize_sweep_result(const SweepResult& result) {
    Writer w;
    w.key(kResultMagic).end();
    w.key("key").text(result.key).end();
    w.key("arrangement").text(result.arrangement).end();
    w.key("level_g").num(result.level_g).end();
    w.key("first_mode_hz").num(result.first_mode_hz).end();
    w.key("frequencies_hz").integer(static_cast<long long>(result.frequencies_hz.size()));
    for (double f : result.frequencies_hz) w.num(f);
    w.end();
    write_lines(w, "settings", "s", result.settings);
    write_rows(w, result.rows);
    w.key("fillings");
    for (const auto& row : result.rows) w.integer(row.filling);
    w.end();
    write_lines(w, "log", "l", result.control_log);
    write_lines(w, "energy", "e", result.energy_log);
    write_lines(w, "transient_channels", "c", result.transient_channels);
    write_lines(w, "series", "s", result.transient_series);
    write_lines(w, "envelope", "v", result.transient_envelope);
    write_lines(w, "random_spectra", "r", result.random_spectra);
    w.key("resumed_points").integer(result.resumed_points).end();
    w.key("periods_simulated").integer(result.periods_simulated).end();
    w.key("end").end();
    return w.str();
}

SweepResult parse_sweep_result(const std::string& text, const std::string& source) {
    Reader r(text, source);
    SweepResult s;
    const auto text_of = [&r](const char* key) {
        r.line(key);
        const auto tab = r.current().find('\t');
        return tab == std::string::npos ? std::string() : r.current().substr(tab + 1);
    };
    r.line(kResultMagic);
    s.key = text_of("key");
    s.arrangement = text_of("arrangement");
    {
        auto words = r.line("level_g");
        s.level_g = r.num(words);
    }
    {
        auto words = r.line("first_mode_hz");
        s.first_mode_hz = r.num(words);
    }
    {
        auto words = r.line("frequencies_hz");
        const long long n = r.integer(words);
        if (n < 0 || n > 100000) r.fail("implausible size");
        for (long long i = 0; i < n; ++i) s.frequencies_hz.push_back(r.num(words));
    }
    s.settings = read_lines(r, "settings", "s");
    s.rows = read_rows(r);
    {
        auto words = r.line("fillings");
        for (auto& row : s.rows) row.filling = static_cast<int>(r.integer(words));
    }
    s.control_log = read_lines(r, "log", "l");
    s.energy_log = read_lines(r, "energy", "e");
    s.transient_channels = read_lines(r, "transient_channels", "c");
    s.transient_series = read_lines(r, "series", "s");
    s.transient_envelope = read_lines(r, "envelope", "v");
    s.random_spectra = read_lines(r, "random_spectra", "r");
    {
        auto words = r.line("resumed_points");
        s.resumed_points = static_cast<int>(r.integer(words));
    }
    {
        auto words = r.line("periods_simulated");
        s.periods_simulated = r.integer(words);
    }
    r.line("end");
    return s;
}

std::string serialize_pour_progress(const dem::PourProgress& p) {
    Writer w;
    w.key(kPourMagic).end();
    w.key("seed").integer(static_cast<long long>(p.seed)).end();
    w.key("settle")
        .integer(p.batch)
        .integer(p.final_settle ? 1 : 0)
        .integer(p.settle_steps)
        .integer(p.quiet_checks)
        .end();
    w.key("generator").text(p.generator_state).end();
    write_dem_state(w, p.solver);
    w.key("end").end();
    return seal_checkpoint(w.str());
}

dem::PourProgress parse_pour_progress(const std::string& text, const std::string& file_name) {
    check_sealed(text, file_name, kPourMagic, kPourMagicPrefix);
    Reader r(std::string(checkpoint_content(text)), file_name);
    dem::PourProgress p;
    r.line(kPourMagic);
    {
        auto words = r.line("seed");
        std::string seed;
        words >> seed;
        char* end = nullptr;
        p.seed = std::strtoull(seed.c_str(), &end, 10);
        if (seed.empty() || *end != '\0') r.fail("'" + seed + "' is not a seed");
        r.end(words);
    }
    {
        auto words = r.line("settle");
        const long long batch = r.integer(words), final_settle = r.integer(words);
        p.settle_steps = r.integer(words);
        const long long quiet = r.integer(words);
        r.end(words);
        if (batch < 0 || batch > kMaxCount || quiet < 0 || quiet > kMaxCount ||
            p.settle_steps < 0 || (final_settle != 0 && final_settle != 1)) {
            r.fail("implausible batch, step or check count");
        }
        p.batch = static_cast<int>(batch);
        p.final_settle = final_settle == 1;
        p.quiet_checks = static_cast<int>(quiet);
    }
    r.line("generator");
    p.generator_state = r.text();
    p.solver = read_dem_state(r);
    r.line("end");
    return p;
}

std::string checkpoint_config_hash(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line != kMagic || !std::getline(in, line)) return {};
    const std::string key = "config_hash\t";
    return line.rfind(key, 0) == 0 ? line.substr(key.size()) : std::string();
}

}  // namespace sb::bench
