// A small typed model with every kind of key, declared the way bench/ declares the campaign.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/builder.hpp"
#include "config/document.hpp"
#include "config/errors.hpp"
#include "config/read.hpp"

namespace sb::config::test {

enum class Colour { red, blue };
inline constexpr std::pair<Colour, std::string_view> kColourNames[] = {{Colour::red, "red"},
                                                                       {Colour::blue, "blue"}};

struct Inner {
    double alpha = 1.0;          ///< its leaf module calls it "alpha_value"
    std::optional<double> beta;  ///< follows alpha
};
struct Wheel {
    std::string name;
    double radius_m = 0.3;
};
struct Spoke {
    double length_m = 0.1;
    int count = 2;
};
struct Point {
    std::string name;
    double x_m = 0.0;
};

struct Model {
    double length_m = 1.0;
    int count = 3;
    std::optional<double> stiffness;  ///< automatic
    std::optional<double> shear;      ///< optional
    bool flag = false;
    Colour colour = Colour::red;
    double blue_only = 2.0;  ///< applies only to blue, rejected otherwise
    std::vector<double> levels;
    std::vector<std::string> names;
    std::string label = "model";
    double position[3] = {0.0, 0.0, 0.0};
    Inner inner;
    std::vector<Wheel> wheels;
    std::vector<Spoke> spokes;
    std::vector<Point> points;
};

/// The inner table's leaf check: alpha at most 10, reported under its leaf name.
inline Violations check_inner(const Inner& inner) {
    Violations v;
    if (inner.alpha > 10.0) {
        v.push_back({"alpha_value", format_value(inner.alpha), "must be <= 10", "leaf meaning"});
    }
    return v;
}

inline const Table& model_schema() {
    static const std::shared_ptr<const Table> schema = [] {
        TableBuilder<Inner> inner("the inner table");
        inner
            .number(
                "alpha", [](Inner & i) -> auto& { return i.alpha; }, "alpha value")
            .unit("Pa")
            .bound(Bound::positive())
            .leaf("alpha_value");
        inner
            .number(
                "beta", [](Inner & i) -> auto& { return i.beta; }, "beta value")
            .unit("Pa")
            .bound(Bound::positive())
            .follows("alpha");
        inner.check([](const Inner& i) { return check_inner(i); });

        TableBuilder<Wheel> wheel("a wheel");
        wheel
            .number(
                "radius_m", [](Wheel & w) -> auto& { return w.radius_m; }, "wheel radius")
            .unit("m")
            .bound(Bound::positive());
        TableBuilder<Spoke> spoke("spokes");
        spoke
            .number(
                "length_m", [](Spoke & s) -> auto& { return s.length_m; }, "spoke length")
            .unit("m")
            .bound(Bound::positive())
            .required();
        spoke
            .integer(
                "count", [](Spoke & s) -> auto& { return s.count; }, "spokes of this kind")
            .bound(Bound::at_least(1));

        TableBuilder<Model> t("the model");
        t.number(
             "length_m", [](Model & m) -> auto& { return m.length_m; }, "length")
            .unit("m")
            .bound(Bound::positive());
        t.integer(
             "count", [](Model & m) -> auto& { return m.count; }, "count")
            .bound(Bound::at_least(1));
        t.number(
             "stiffness", [](Model & m) -> auto& { return m.stiffness; }, "stiffness")
            .unit("N/m")
            .bound(Bound::positive())
            .automatic("chosen by the bench");
        t.number(
             "shear", [](Model & m) -> auto& { return m.shear; }, "shear modulus")
            .unit("Pa")
            .bound(Bound::positive())
            .optional();
        t.boolean(
            "flag", [](Model & m) -> auto& { return m.flag; }, "a flag");
        t.choice(
            "colour", [](Model & m) -> auto& { return m.colour; }, kColourNames, "colour");
        t.number(
             "blue_only", [](Model & m) -> auto& { return m.blue_only; }, "blue setting")
            .bound(Bound::positive())
            .when([](const Model& m) { return m.colour == Colour::blue; },
                  "only for colour = \"blue\"", true);
        t.numbers(
             "levels", [](Model & m) -> auto& { return m.levels; }, "levels")
            .unit("g")
            .bound(Bound::positive());
        t.strings(
            "names", [](Model & m) -> auto& { return m.names; }, "names");
        t.string(
            "label", [](Model & m) -> auto& { return m.label; }, "label");
        t.vector3(
             "position", [](Model & m) -> auto& { return m.position; }, "position")
            .unit("m");
        t.table(
            "inner", [](Model & m) -> auto& { return m.inner; }, inner.build());
        t.named_tables(
            "wheels", [](Model & m) -> auto& { return m.wheels; },
            [](Wheel & w) -> auto& { return w.name; }, wheel.build());
        t.array_of_tables(
            "spokes", [](Model & m) -> auto& { return m.spokes; }, spoke.build());
        Declaration point;
        point.type = Type::number;
        point.unit = "m";
        point.bound = Bound::non_negative();
        point.meaning = "point position";
        t.named_numbers(
            "points", [](Model & m) -> auto& { return m.points; },
            [](Point & p) -> auto& { return p.name; }, [](Point & p) -> auto& { return p.x_m; },
            point, "named points");
        // Across keys: the count cannot exceed the number of levels when levels are given.
        t.check([](const Model& m) {
            Violations v;
            if (!m.levels.empty() && m.count > static_cast<int>(m.levels.size())) {
                v.push_back(
                    {"count", std::to_string(m.count), "must be <= the number of levels", ""});
            }
            return v;
        });
        return t.build();
    }();
    return *schema;
}

/// Reads `text` into a Model; the errors found, formatted, in `errors`.
inline Model read_model(const std::string& text, std::vector<std::string>& errors,
                        SourceMap* where = nullptr) {
    Model m;
    errors.clear();
    try {
        auto document = Document::parse_text(text, "t.toml");
        Diagnostics diagnostics;
        read(model_schema(), *document, &m, diagnostics);
        SourceMap map;
        map.document = document;
        check(model_schema(), &m, map, diagnostics);
        if (where != nullptr) *where = map;
        diagnostics.throw_if_any();
    } catch (const ConfigException& e) {
        for (const auto& error : e.errors()) errors.push_back(error.format());
    }
    return m;
}

}  // namespace sb::config::test
