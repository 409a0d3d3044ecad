// Sweep checkpoints: exact text form of a sweep's progress and state.
#include "bench/sweep_checkpoint.hpp"

#include <sstream>
#include <stdexcept>

namespace sb::bench {
namespace {

constexpr const char* kMagic = "shakerbench-sweep-checkpoint 2";

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

std::string serialize_checkpoint(const SweepCheckpoint& c) {
    Writer w;
    w.key(kMagic).end();
    w.key("config_hash").text(c.config_hash).end();
    w.key("points_done").integer(c.points_done).end();
    w.key("next_amplitude").num(c.next_amplitude).end();
    write_vector(w, "q", c.state.q);
    write_vector(w, "q_dot", c.state.q_dot);
    w.key("dampers").integer(static_cast<long long>(c.state.particles.size())).end();
    for (std::size_t d = 0; d < c.state.particles.size(); ++d) {
        w.key("load");
        for (int k = 0; k < 6; ++k) {
            w.num(c.state.damper_loads[d][k]);
        }
        w.end();
        const auto& p = c.state.particles[d];
        w.key("particles").integer(static_cast<long long>(p.positions_m.size())).end();
        for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
            w.key("p");
            for (int k = 0; k < 3; ++k) w.num(p.positions_m[i][k]);
            w.num(p.radii_m[i]);
            for (int k = 0; k < 3; ++k) w.num(p.velocities_m_s[i][k]);
            for (int k = 0; k < 3; ++k) w.num(p.angular_velocities_rad_s[i][k]);
            w.end();
        }
    }
    w.key("rows").integer(static_cast<long long>(c.rows.size())).end();
    for (const auto& row : c.rows) {
        w.key("row")
            .num(row.level_g)
            .num(row.frequency_hz)
            .integer(static_cast<long long>(row.values.size()));
        for (const auto& v : row.values) {
            w.num(v.rms).num(v.amplitude.real()).num(v.amplitude.imag());
        }
        w.text(row.arrangement).text(row.status).text(row.series.empty() ? "-" : row.series);
        w.end();
    }
    w.key("log").integer(static_cast<long long>(c.control_log.size())).end();
    for (const auto& l : c.control_log) {
        w.key("l").text(l).end();
    }
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
    auto dampers_line = r.line("dampers");
    const long long dampers = r.integer(dampers_line);
    for (long long d = 0; d < dampers; ++d) {
        auto load = r.line("load");
        Eigen::Matrix<double, 6, 1> l;
        for (int k = 0; k < 6; ++k) l[k] = r.num(load);
        c.state.damper_loads.push_back(l);
        auto count_line = r.line("particles");
        const long long count = r.integer(count_line);
        dem::ParticleSet p;
        for (long long i = 0; i < count; ++i) {
            auto words = r.line("p");
            Eigen::Vector3d x, v, w;
            for (int k = 0; k < 3; ++k) x[k] = r.num(words);
            const double radius = r.num(words);
            for (int k = 0; k < 3; ++k) v[k] = r.num(words);
            for (int k = 0; k < 3; ++k) w[k] = r.num(words);
            p.positions_m.push_back(x);
            p.radii_m.push_back(radius);
            p.velocities_m_s.push_back(v);
            p.angular_velocities_rad_s.push_back(w);
        }
        c.state.particles.push_back(std::move(p));
    }
    auto rows_line = r.line("rows");
    const long long rows = r.integer(rows_line);
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
        c.rows.push_back(std::move(row));
    }
    auto log_line = r.line("log");
    const long long logs = r.integer(log_line);
    for (long long i = 0; i < logs; ++i) {
        r.line("l");
        const auto tab = r.current().find('\t');
        c.control_log.push_back(tab == std::string::npos ? "" : r.current().substr(tab + 1));
    }
    r.line("end");
    return c;
}

std::string checkpoint_config_hash(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line != kMagic || !std::getline(in, line)) return {};
    const std::string key = "config_hash\t";
    return line.rfind(key, 0) == 0 ? line.substr(key.size()) : std::string();
}

}  // namespace sb::bench
