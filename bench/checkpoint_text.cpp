// The exact text form of checkpoints: records, DEM states, energy ledgers, the seal.
#include "bench/checkpoint_text.hpp"

#include <algorithm>
#include <cstdlib>

#include "config/write.hpp"

namespace sb::bench::checkpoint {
namespace {

std::uint32_t read_id(Reader& r, std::istringstream& words) {
    const long long v = r.integer(words);
    if (v < 0 || v > 0xffffffffLL) r.fail("implausible id");
    return static_cast<std::uint32_t>(v);
}

}  // namespace

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
    if (n < 0 || n > kMaxVectorSize) {
        r.fail("implausible size " + std::to_string(n));
    }
    Eigen::VectorXd v(n);
    for (long long i = 0; i < n; ++i) {
        v[i] = r.num(words);
    }
    r.end(words);
    return v;
}

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

long long read_count(Reader& r, const char* key) {
    auto words = r.line(key);
    const long long n = r.integer(words);
    if (n < 0 || n > kMaxCount) r.fail("implausible count " + std::to_string(n));
    r.end(words);
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
        r.end(words);
    }
    const long long particles = read_count(r, "particles");
    for (long long i = 0; i < particles; ++i) {
        auto words = r.line("p");
        s.positions_m.push_back(read_vector3(r, words));
        s.radii_m.push_back(r.num(words));
        s.velocities_m_s.push_back(read_vector3(r, words));
        s.angular_velocities_rad_s.push_back(read_vector3(r, words));
        r.end(words);
    }
    const long long pairs = read_count(r, "pairs");
    for (long long i = 0; i < pairs; ++i) {
        auto words = r.line("h");
        dem::PairHistory h;
        h.i = read_id(r, words);
        h.j = read_id(r, words);
        h.history_m = read_vector3(r, words);
        r.end(words);
        s.pair_histories.push_back(h);
    }
    const long long walls = read_count(r, "walls");
    for (long long i = 0; i < walls; ++i) {
        auto words = r.line("w");
        dem::WallHistory h;
        h.particle = read_id(r, words);
        h.wall = read_id(r, words);
        h.history_m = read_vector3(r, words);
        r.end(words);
        s.wall_histories.push_back(h);
    }
    const long long locked = read_count(r, "locked");
    for (long long i = 0; i < locked; ++i) {
        auto words = r.line("k");
        dem::LockedParticle l;
        l.id = read_id(r, words);
        l.position_m = read_vector3(r, words);
        r.end(words);
        s.locked.push_back(l);
    }
    {
        auto words = r.line("clock");
        const long long released = r.integer(words);
        if (released != 0 && released != 1) r.fail("released must be 0 or 1");
        s.released = released == 1;
        s.time_s = r.num(words);
        s.step = r.integer(words);
        r.end(words);
    }
    {
        auto words = r.line("layers");
        s.layers_up = read_vector3(r, words);
        r.end(words);
    }
    return s;
}

void write_ledger(Writer& w, const dem::EnergyLedger& e) {
    w.key("ledger")
        .num(e.wall_work)
        .num(e.normal_damping)
        .num(e.friction)
        .num(e.rolling)
        .num(e.kinetic_translational)
        .num(e.kinetic_rotational)
        .num(e.potential)
        .num(e.elastic)
        .num(e.initial_total)
        .end();
    write_vector(
        w, "layer_dissipation",
        Eigen::Map<const Eigen::VectorXd>(e.layer_dissipation.data(),
                                          static_cast<Eigen::Index>(e.layer_dissipation.size())));
    write_vector(
        w, "layer_kinetic_time",
        Eigen::Map<const Eigen::VectorXd>(e.layer_kinetic_time.data(),
                                          static_cast<Eigen::Index>(e.layer_kinetic_time.size())));
}

dem::EnergyLedger read_ledger(Reader& r) {
    dem::EnergyLedger e;
    auto words = r.line("ledger");
    for (double* v :
         {&e.wall_work, &e.normal_damping, &e.friction, &e.rolling, &e.kinetic_translational,
          &e.kinetic_rotational, &e.potential, &e.elastic, &e.initial_total}) {
        *v = r.num(words);
    }
    r.end(words);
    const Eigen::VectorXd dissipation = read_vector(r, "layer_dissipation");
    e.layer_dissipation.assign(dissipation.begin(), dissipation.end());
    const Eigen::VectorXd kinetic_time = read_vector(r, "layer_kinetic_time");
    e.layer_kinetic_time.assign(kinetic_time.begin(), kinetic_time.end());
    return e;
}

void check_sealed(const std::string& text, const std::string& file, std::string_view magic,
                  std::string_view magic_prefix) {
    if (text.rfind(magic_prefix, 0) != 0) {
        throw CheckpointError(
            file, 1,
            "not a checkpoint: it does not start with '" + std::string(magic_prefix) + "'");
    }
    const std::string first = text.substr(0, text.find('\n'));
    if (first != magic) {
        throw CheckpointError(file, 1,
                              "checkpoint format '" + first.substr(magic_prefix.size()) +
                                  "', this shakerbench reads format '" +
                                  std::string(magic.substr(magic_prefix.size())) + "'");
    }
    const std::string_view content = checkpoint_content(text);
    if (content.size() == text.size()) {
        const auto lines = std::count(text.begin(), text.end(), '\n') +
                           (text.empty() || text.back() == '\n' ? 0 : 1);
        throw CheckpointError(file, static_cast<int>(lines),
                              "truncated: the file ends without its checksum line (cut short)");
    }
    const std::string expected = config::fnv1a_hex(content);
    const std::string_view found =
        std::string_view(text).substr(content.size() + kChecksumKey.size());
    if (found.substr(0, found.size() - 1) != expected) {
        throw CheckpointError(file, 0,
                              "corrupted: its content does not match the checksum on its last "
                              "line (the content gives " +
                                  expected + ")");
    }
}

}  // namespace sb::bench::checkpoint
