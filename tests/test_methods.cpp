// The method declarations (gi/method.h): every settings table accepts its defaults and both ends of
// every range and refuses one step past them with the key named; every built method plans
// without GL; docs/methods.md is what `voxgi methods --markdown` prints.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "gi/methods.h"
#include "scenes/errors.h"
#include "support/test_support.h"

namespace voxgi {
namespace {

struct Checker {
    const MethodInfo& method;
    const SettingInfo& setting;

    void accepts(const std::string& text) const {
        GiSettings gi;
        gi.set(setting.key, text);
        try {
            method.validate(gi);
        } catch (const std::exception& e) {
            ADD_FAILURE() << method.name << ": " << setting.key << "=" << text << " refused: " << e.what();
        }
    }

    void refuses(const std::string& text) const {
        GiSettings gi;
        gi.set(setting.key, text);
        try {
            method.validate(gi);
            ADD_FAILURE() << method.name << ": " << setting.key << "=" << text << " accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("gi." + setting.key + ":"), std::string::npos)
                << "the error does not name the key: " << e.what();
        }
    }
};

// Just outside [min, max]: a thousandth of the bound's size (at least 1e-3) beyond it.
double below(double min) { return min - std::max(std::abs(min), 1.0) * 1e-3; }
double above(double max) { return max + std::max(std::abs(max), 1.0) * 1e-3; }

std::string triple(double a, double b, double c) {
    return formatNumber(a) + "," + formatNumber(b) + "," + formatNumber(c);
}

void walk(const MethodInfo& m, const SettingInfo& s) {
    Checker c{m, s};
    c.accepts(s.defaultText);
    switch (s.kind) {
        case SettingKind::Integer:
            c.accepts(formatNumber(s.min));
            c.accepts(formatNumber(s.max));
            c.refuses(formatNumber(s.min - s.step));
            c.refuses(formatNumber(s.max + s.step));
            if (s.step > 1 && s.min + 1 < s.max) c.refuses(formatNumber(s.min + 1));
            c.refuses("1.5");
            c.refuses("many");
            if (!s.fitWord.empty()) c.accepts(s.fitWord);
            break;
        case SettingKind::Number:
            c.accepts(formatNumber(s.min));
            c.accepts(formatNumber(s.max));
            c.refuses(formatNumber(below(s.min)));
            c.refuses(formatNumber(above(s.max)));
            c.refuses("nan");
            c.refuses("inf");
            c.refuses("0.5x");
            break;
        case SettingKind::Flag:
            c.accepts("true");
            c.accepts("false");
            c.refuses("maybe");
            break;
        case SettingKind::Choice:
            for (const std::string& choice : s.choices) c.accepts(choice);
            c.refuses("no-such-choice");
            break;
        case SettingKind::Triple:
            // Each end on one axis with the others at the minimum (a grid of 256^3 probes is
            // refused as a whole, 256 on one axis is not).
            c.accepts(triple(s.max, s.min, s.min));
            c.accepts(triple(s.min, s.min, s.max));
            c.accepts(formatNumber(s.min));
            c.refuses(triple(above(s.max), s.min, s.min));
            c.refuses(triple(s.min, below(s.min), s.min));
            c.refuses("1,2");
            c.refuses("1,2,3,4");
            if (!s.fitWord.empty()) c.accepts(s.fitWord);
            if (s.whole && s.min + 1.5 <= s.max) c.refuses(formatNumber(s.min + 0.5));
            break;
    }
}

TEST(MethodSettings, EveryRangeEndAcceptedAndOnePastRefusedWithTheKey) {
    int walked = 0;
    for (const MethodInfo& m : methods()) {
        if (!m.built) continue;
        EXPECT_NO_THROW(m.validate(GiSettings{})) << m.name << ": its defaults";
        for (const SettingInfo& s : m.settings) {
            EXPECT_EQ(s.key.rfind(m.section + ".", 0), 0u) << s.key << " is outside the section " << m.section;
            EXPECT_FALSE(s.doc.empty()) << s.key;
            walk(m, s);
            ++walked;
        }
        // A key of the section that the table does not declare is an error naming it.
        if (!m.section.empty()) {
            GiSettings gi;
            gi.set(m.section + ".no_such_key", "1");
            try {
                m.validate(gi);
                ADD_FAILURE() << m.name << " accepted an unknown key";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find(m.section + ".no_such_key"), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_GT(walked, 40);
}

TEST(MethodSettings, OneBackendVocabulary) {
    for (const MethodInfo& m : methods())
        for (const SettingInfo& s : m.settings)
            if (s.key == m.section + ".backend") {
                EXPECT_EQ(s.kind, SettingKind::Choice) << s.key;
                EXPECT_EQ(s.choices, (std::vector<std::string>{"cpu", "gl"})) << s.key;
            }
    GiSettings gi;
    setForEveryMethod(gi, "backend", "gl");
    EXPECT_EQ(gi.getString("lpv.backend", ""), "gl");
    EXPECT_EQ(gi.getString("ddgi.backend", ""), "gl");
    EXPECT_THROW(setForEveryMethod(gi, "backend", "gpu"), InputError);
}

TEST(MethodList, BuiltMethodsPlanWithoutGlAndPlannedOnesSaySo) {
    Scene scene = test::cornellBox();
    for (const MethodInfo& m : methods()) {
        if (!m.built) {
            EXPECT_THROW(findMethod(m.name), NotImplementedError) << m.name;
            continue;
        }
        ASSERT_TRUE(m.plan) << m.name;
        TechniquePlan plan = m.plan(scene);
        // A pass name is a timer stage of the method's section, or of the method it runs inside
        // (isr's far field, hybrid's diffuse method: by default clpv, section lpv).
        const std::string inner = m.name == "hybrid" ? "lpv." : m.section + ".";
        for (const auto* list : {&plan.update, &plan.apply})
            for (const PlannedPass& p : *list) {
                EXPECT_FALSE(p.reason.empty()) << p.name;
                EXPECT_TRUE(p.name.rfind(m.section + ".", 0) == 0 || p.name.rfind(inner, 0) == 0) << m.name << ": " << p.name;
            }
        for (const Preset& p : m.presets) {
            Scene s = scene;
            for (const auto& [k, v] : p.settings) s.gi.set(k, v);
            EXPECT_NO_THROW(m.validate(s.gi)) << m.name << " preset " << p.name;
        }
        for (const Preset& p : m.benchVariants) {
            GiSettings gi;
            for (const auto& [k, v] : p.settings) gi.set(k, v);
            EXPECT_NO_THROW(m.validate(gi)) << m.name << " bench variant " << p.name;
        }
        for (const DebugViewInfo& v : m.debugViews)
            for (const SettingInfo& o : v.options) EXPECT_EQ(o.key.rfind(v.name + ".", 0), 0u) << o.key;
    }
    EXPECT_THROW(findMethod("magic"), InputError);
}

TEST(MethodDocs, MethodsPageIsTheGeneratedOne) {
    test::RunResult r = test::runVoxgi("methods --markdown");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(test::sourcePath("docs/methods.md"));
    std::stringstream file;
    file << in.rdbuf();
    EXPECT_EQ(file.str(), r.output) << "docs/methods.md is stale: ./build/tools/voxgi methods --markdown > docs/methods.md";
}

}  // namespace
}  // namespace voxgi
