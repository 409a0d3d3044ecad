#include "correlation/free_parameters.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "bench/config_schema.hpp"
#include "config/dotted_path.hpp"
#include "config/errors.hpp"

namespace sb::correlation {
namespace {

std::optional<double> parse_number(std::string_view text) {
    while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    double value = 0.0;
    const auto* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

std::optional<double> number_of(const config::Value& value) {
    if (const auto* d = std::get_if<double>(&value)) return *d;
    if (const auto* i = std::get_if<long>(&value)) return static_cast<double>(*i);
    return std::nullopt;
}

}  // namespace

std::string exact_text(double value) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
}

std::vector<FreeParameter> parse_free_parameters(const bench::CampaignConfig& config,
                                                 const std::vector<std::string>& items,
                                                 const std::string& origin) {
    config::Diagnostics diagnostics;
    std::vector<FreeParameter> free;
    const auto fail = [&](const std::string& key, const std::string& value,
                          const std::string& constraint, const std::string& meaning) {
        diagnostics.add(config::ConfigError{origin, 0, 0, key, value, constraint, meaning});
    };
    for (const auto& item : items) {
        std::string key = item;
        std::string interval;
        if (const auto eq = item.find('='); eq != std::string::npos) {
            key = item.substr(0, eq);
            interval = item.substr(eq + 1);
        }
        const config::Declaration* decl = nullptr;
        try {
            decl = &config::declaration(bench::campaign_schema(), &config, key);
        } catch (const config::ConfigException&) {
            fail(key, interval, "names no value of the config", "--free KEY=MIN:MAX");
            continue;
        }
        if (decl->type != config::Type::number) {
            fail(key, interval, "is not a number, so it cannot be calibrated",
                 decl->meaning_with_unit());
            continue;
        }
        FreeParameter p;
        p.path = key;
        p.meaning = decl->meaning_with_unit();
        if (interval.empty()) {
            if (!decl->calibration_range) {
                fail(key, "", "has no default search interval: give KEY=MIN:MAX", p.meaning);
                continue;
            }
            p.lo = (*decl->calibration_range)[0];
            p.hi = (*decl->calibration_range)[1];
        } else {
            // MIN:MAX, or MIN:MAX:log.
            std::string_view bounds = interval;
            if (bounds.size() > 4 && bounds.substr(bounds.size() - 4) == ":log") {
                p.log_scale = true;
                bounds.remove_suffix(4);
            }
            const auto colon = bounds.find(':');
            const auto lo =
                colon == std::string::npos ? std::nullopt : parse_number(bounds.substr(0, colon));
            const auto hi =
                colon == std::string::npos ? std::nullopt : parse_number(bounds.substr(colon + 1));
            if (!lo || !hi) {
                fail(key, interval, "must be MIN:MAX or MIN:MAX:log, two finite numbers",
                     p.meaning);
                continue;
            }
            if (!(*lo < *hi)) {
                fail(key, interval, "MIN must be less than MAX", p.meaning);
                continue;
            }
            if (p.log_scale && !(*lo > 0.0)) {
                fail(key, interval, "a log scale needs MIN > 0", p.meaning);
                continue;
            }
            p.lo = *lo;
            p.hi = *hi;
        }
        if (!decl->bound.contains(p.lo) || !decl->bound.contains(p.hi)) {
            fail(key, exact_text(p.lo) + ":" + exact_text(p.hi),
                 "the interval must lie within the key's bound " + decl->bound.text(), p.meaning);
            continue;
        }
        const auto current = number_of(config::get(bench::campaign_schema(), &config, key));
        p.start = std::clamp(current.value_or(0.5 * (p.lo + p.hi)), p.lo, p.hi);
        const bool duplicate = std::any_of(free.begin(), free.end(),
                                           [&](const FreeParameter& f) { return f.path == key; });
        if (duplicate) {
            fail(key, interval, "is freed twice", p.meaning);
            continue;
        }
        free.push_back(p);
    }
    if (items.empty()) fail("--free", "", "frees no key", "KEY=MIN:MAX or KEY");
    diagnostics.throw_if_any();
    return free;
}

std::vector<FreeParameter> default_free_parameters(const bench::CampaignConfig& config) {
    std::vector<std::string> items;
    for (const auto& damper : config.campaign.dampers) {
        if (damper.model != bench::DamperSpec::Model::dem) continue;
        const std::string prefix = config::join_path("dampers", damper.name) + ".contact.";
        for (const char* key : {"sliding_friction", "rolling_friction", "restitution"}) {
            items.push_back(prefix + key);
        }
    }
    if (items.empty()) {
        throw config::ConfigException({config::ConfigError{
            config.source, 0, 0, "dampers", "",
            "no damper with model = \"dem\": name the keys to calibrate with --free KEY=MIN:MAX",
            "the default free set is the particles' friction and restitution"}});
    }
    return parse_free_parameters(config, items, "default free set");
}

double FreeParameter::value_at(double u) const {
    const double t = std::clamp(u, 0.0, 1.0);
    if (log_scale) return t >= 1.0 ? hi : lo * std::pow(hi / lo, t);
    return lo + t * (hi - lo);
}

double FreeParameter::unit_of(double value) const {
    if (log_scale) return std::log(value / lo) / std::log(hi / lo);
    return (value - lo) / (hi - lo);
}

std::vector<double> to_values(const std::vector<FreeParameter>& free,
                              const std::vector<double>& u) {
    std::vector<double> v(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) v[i] = free[i].value_at(u[i]);
    return v;
}

std::vector<double> to_unit(const std::vector<FreeParameter>& free,
                            const std::vector<double>& values) {
    std::vector<double> u(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) u[i] = free[i].unit_of(values[i]);
    return u;
}

bench::CampaignConfig with_values(const bench::CampaignConfig& config,
                                  const std::vector<FreeParameter>& free,
                                  const std::vector<double>& values) {
    bench::CampaignConfig changed = config;
    std::vector<std::string> assignments;
    for (std::size_t i = 0; i < free.size(); ++i) {
        assignments.push_back(free[i].path + "=" + exact_text(values[i]));
    }
    bench::apply_overrides(changed, assignments, "calibration");
    return changed;
}

}  // namespace sb::correlation
