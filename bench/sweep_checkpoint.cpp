// Sweep checkpoints: exact text form of a sweep's progress and state.
#include "bench/sweep_checkpoint.hpp"

#include <sstream>
#include <stdexcept>

namespace sb::bench {
namespace {

constexpr const char* kMagic = "shakerbench-sweep-checkpoint 3";
constexpr const char* kResultMagic = "shakerbench-sweep-result 1";

class Writer {
  public:
    Writer() { out_ << std::hexfloat; }
    Writer& key(const char* k) {
        out_ << k;
        return *this;
    }
    Writer& num(double v) {
        out_ << ' ' << v;
        return *this;
    }
    Writer& integer(long long v) {
        out_ << ' ' << v;
        return *this;
    }
    Writer& text(const std::string& t) {
        out_ << '\t' << t;
        return *this;
    }
    void end() { out_ << '\n'; }
    std::string str() const { return out_.str(); }

  private:
    std::ostringstream out_;
};

class Reader {
  public:
    Reader(const std::string& text, std::string file) : in_(text), file_(std::move(file)) {}

    /// Next line, which must start with `key`; its remaining words follow in `rest`.
    std::istringstream line(const std::string& key) {
        std::string l;
        if (!std::getline(in_, l)) {
            fail("ends early, expected '" + key + "'");
        }
        ++line_;
        if (l.rfind(key, 0) != 0) {
            fail("expected '" + key + "'");
        }
        current_ = l;
        return std::istringstream(l.substr(key.size()));
    }
    double num(std::istringstream& words) {
        std::string w;
        if (!(words >> w)) {
            fail("a number is missing");
        }
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);
        if (end == w.c_str() || *end != '\0') {
            fail("'" + w + "' is not a number");
        }
        return v;
    }
    long long integer(std::istringstream& words) {
        long long v = 0;
        if (!(words >> v)) {
            fail("a whole number is missing");
        }
        return v;
    }
    [[noreturn]] void fail(const std::string& message) const {
        throw std::runtime_error(file_ + ":" + std::to_string(line_) + ": " + message +
                                 " (a damaged checkpoint: delete it to recompute that sweep)");
    }
    const std::string& current() const { return current_; }

  private:
    std::istringstream in_;
    std::string file_;
    std::string current_;
    int line_ = 0;
};

void write_vector(Writer& w, const char* key, const Eigen::VectorXd& v) {
    w.key(key).integer(v.size());
    for (Eigen::Index i = 0; i < v.size(); ++i) {
        w.num(v[i]);
    }
    w.end();
}

Eigen::VectorXd read_vector(Reader& r, const char* key) {
    auto words = r.line(key);
    const long long n = r.integer(words);
    if (n < 0 || n > 100000) {
        r.fail("implausible size");
    }
    Eigen::VectorXd v(n);
    for (long long i = 0; i < n; ++i) {
        v[i] = r.num(words);
    }
    return v;
}

}  // namespace

namespace {

void write_vector3(Writer& w, const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) w.num(v[k]);
}

Eigen::Vector3d read_vector3(Reader& r, std::istringstream& words) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = r.num(words);
    return v;
}

void write_dem_state(Writer& w, const dem::SolverState& s) {
    w.key("enclosure");
    write_vector3(w, s.enclosure.position_m);
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) w.num(s.enclosure.rotation(a, b));
    }
    write_vector3(w, s.enclosure.velocity_m_s);
    write_vector3(w, s.enclosure.angular_velocity_rad_s);
    w.end();
    w.key("particles").integer(static_cast<long long>(s.positions_m.size())).end();
    for (std::size_t i = 0; i < s.positions_m.size(); ++i) {
        w.key("p");
        write_vector3(w, s.positions_m[i]);
        w.num(s.radii_m[i]);
        write_vector3(w, s.velocities_m_s[i]);
        write_vector3(w, s.angular_velocities_rad_s[i]);
        w.end();
    }
    w.key("pairs").integer(static_cast<long long>(s.pair_histories.size())).end();
    for (const auto& h : s.pair_histories) {
        w.key("h").integer(h.i).integer(h.j);
        write_vector3(w, h.history_m);
        w.end();
    }
    w.key("walls").integer(static_cast<long long>(s.wall_histories.size())).end();
    for (const auto& h : s.wall_histories) {
        w.key("w").integer(h.particle).integer(h.wall);
        write_vector3(w, h.history_m);
        w.end();
    }
    w.key("locked").integer(static_cast<long long>(s.locked.size())).end();
    for (const auto& l : s.locked) {
        w.key("k").integer(l.id);
        write_vector3(w, l.position_m);
        w.end();
    }
    w.key("clock").integer(s.released ? 1 : 0).num(s.time_s).integer(s.step).end();
    w.key("layers");
    write_vector3(w, s.layers_up);
    w.end();
}

std::uint32_t read_id(Reader& r, std::istringstream& words) {
    const long long v = r.integer(words);
    if (v < 0 || v > 0xffffffffLL) r.fail("implausible id");
    return static_cast<std::uint32_t>(v);
}

long long read_count(Reader& r, const char* key) {
    auto words = r.line(key);
    const long long n = r.integer(words);
    if (n < 0 || n > 100000000) r.fail("implausible count");
    return n;
}

dem::SolverState read_dem_state(Reader& r) {
    dem::SolverState s;
    {
        auto words = r.line("enclosure");
        s.enclosure.position_m = read_vector3(r, words);
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) s.enclosure.rotation(a, b) = r.num(words);
        }
        s.enclosure.velocity_m_s = read_vector3(r, words);
        s.enclosure.angular_velocity_rad_s = read_vector3(r, words);
    }
    const long long particles = read_count(r, "particles");
    for (long long i = 0; i < particles; ++i) {
        auto words = r.line("p");
        s.positions_m.push_back(read_vector3(r, words));
        s.radii_m.push_back(r.num(words));
        s.velocities_m_s.push_back(read_vector3(r, words));
        s.angular_velocities_rad_s.push_back(read_vector3(r, words));
    }
    const long long pairs = read_count(r, "pairs");
    for (long long i = 0; i < pairs; ++i) {
        auto words = r.line("h");
        dem::PairHistory h;
        h.i = read_id(r, words);
        h.j = read_id(r, words);
        h.history_m = read_vector3(r, words);
        s.pair_histories.push_back(h);
    }
    const long long walls = read_count(r, "walls");
    for (long long i = 0; i < walls; ++i) {
        auto words = r.line("w");
        dem::WallHistory h;
        h.particle = read_id(r, words);
        h.wall = read_id(r, words);
        h.history_m = read_vector3(r, words);
        s.wall_histories.push_back(h);
    }
    const long long locked = read_count(r, "locked");
    for (long long i = 0; i < locked; ++i) {
        auto words = r.line("k");
        dem::LockedParticle l;
        l.id = read_id(r, words);
        l.position_m = read_vector3(r, words);
        s.locked.push_back(l);
    }
    {
        auto words = r.line("clock");
        s.released = r.integer(words) != 0;
        s.time_s = r.num(words);
        s.step = r.integer(words);
    }
    {
        auto words = r.line("layers");
        s.layers_up = read_vector3(r, words);
    }
    return s;
}

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

std::vector<identification::PointRow> read_rows(Reader& r) {
    std::vector<identification::PointRow> out;
    const long long rows = read_count(r, "rows");
    for (long long i = 0; i < rows; ++i) {
        auto words = r.line("row");
        identification::PointRow row;
        row.level_g = r.num(words);
        row.frequency_hz = r.num(words);
        const long long values = r.integer(words);
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
        std::string rest;
        std::getline(words, rest);
        std::istringstream fields(rest);
        std::string skip;
        std::getline(fields, skip, '\t');
        if (!std::getline(fields, row.arrangement, '\t') ||
            !std::getline(fields, row.status, '\t') || !std::getline(fields, row.series, '\t')) {
            r.fail("a row lacks its arrangement, status or series");
        }
        if (row.series == "-") {
            row.series.clear();
        }
        out.push_back(std::move(row));
    }
    return out;
}

/// "KEY n", then n lines "LINE_KEY<tab>text".
void write_lines(Writer& w, const char* key, const char* line_key,
                 const std::vector<std::string>& lines) {
    w.key(key).integer(static_cast<long long>(lines.size())).end();
    for (const auto& l : lines) {
        w.key(line_key).text(l).end();
    }
}

std::vector<std::string> read_lines(Reader& r, const char* key, const char* line_key) {
    std::vector<std::string> out;
    const long long count = read_count(r, key);
    for (long long i = 0; i < count; ++i) {
        r.line(line_key);
        const auto tab = r.current().find('\t');
        out.push_back(tab == std::string::npos ? "" : r.current().substr(tab + 1));
    }
    return out;
}

}  // namespace

std::string serialize_checkpoint(const SweepCheckpoint& c) {
    Writer w;
    w.key(kMagic).end();
    w.key("config_hash").text(c.config_hash).end();
    w.key("points_done").integer(c.points_done).end();
    w.key("next_amplitude").num(c.next_amplitude).end();
    write_vector(w, "q", c.state.q);
    write_vector(w, "q_dot", c.state.q_dot);
    w.key("attachments").integer(static_cast<long long>(c.state.attachments.size())).end();
    for (std::size_t d = 0; d < c.state.attachments.size(); ++d) {
        const auto& a = c.state.attachments[d];
        w.key("attachment").text(a.dem ? "dem" : "none").end();
        w.key("load");
        for (int k = 0; k < 6; ++k) w.num(c.state.loads[d][k]);
        w.end();
        if (a.dem) write_dem_state(w, *a.dem);
    }
    write_rows(w, c.rows);
    write_lines(w, "log", "l", c.control_log);
    write_lines(w, "energy", "e", c.energy_log);
    w.key("end").end();
    return w.str();
}

SweepCheckpoint parse_checkpoint(const std::string& text, const std::string& file_name) {
    Reader r(text, file_name);
    SweepCheckpoint c;
    r.line(kMagic);
    {
        r.line("config_hash");
        const auto tab = r.current().find('\t');
        c.config_hash = tab == std::string::npos ? "" : r.current().substr(tab + 1);
    }
    {
        auto words = r.line("points_done");
        c.points_done = static_cast<int>(r.integer(words));
    }
    {
        auto words = r.line("next_amplitude");
        c.next_amplitude = r.num(words);
    }
    c.state.q = read_vector(r, "q");
    c.state.q_dot = read_vector(r, "q_dot");
    const long long attachments = read_count(r, "attachments");
    for (long long d = 0; d < attachments; ++d) {
        r.line("attachment");
        const auto tab = r.current().find('\t');
        const std::string kind = tab == std::string::npos ? "" : r.current().substr(tab + 1);
        if (kind != "dem" && kind != "none") r.fail("unknown attachment '" + kind + "'");
        auto load = r.line("load");
        Eigen::Matrix<double, 6, 1> l;
        for (int k = 0; k < 6; ++k) l[k] = r.num(load);
        c.state.loads.push_back(l);
        AttachmentState a;
        if (kind == "dem") a.dem = read_dem_state(r);
        c.state.attachments.push_back(std::move(a));
    }
    c.rows = read_rows(r);
    c.control_log = read_lines(r, "log", "l");
    c.energy_log = read_lines(r, "energy", "e");
    r.line("end");
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

std::string checkpoint_config_hash(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line != kMagic || !std::getline(in, line)) return {};
    const std::string key = "config_hash\t";
    return line.rfind(key, 0) == 0 ? line.substr(key.size()) : std::string();
}

}  // namespace sb::bench
